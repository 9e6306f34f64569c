"""plugin.xml parsing (no Qt, no ROS): every <class> of every <library> becomes a descriptor."""
import os
import xml.etree.ElementTree as ET


class PluginXmlError(Exception):
    pass


def _icon(elem, base_dir):
    icon = elem.find('icon') if elem is not None else None
    if icon is None or not (icon.text or '').strip():
        return None
    kind = icon.get('type', 'file')
    value = icon.text.strip()
    if kind == 'file':
        value = os.path.join(base_dir, value)
    return {'type': kind, 'value': value}


def _text(elem, tag):
    if elem is None:
        return None
    child = elem.find(tag)
    return child.text.strip() if child is not None and child.text else None


def parse_plugin_xml(path, package_name, base_class_type=None):
    """Descriptors of the classes in plugin.xml `path` of package `package_name`.

    Classes whose base_class_type differs from `base_class_type` (when given) are skipped.
    Raises PluginXmlError (one line naming the file) when the file is missing or not XML.
    """
    if not os.path.isfile(path):
        raise PluginXmlError('plugin.xml "%s" of package "%s" not found' % (path, package_name))
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise PluginXmlError('could not parse plugin.xml "%s": %s' % (path, e))
    base_dir = os.path.dirname(os.path.abspath(path))
    libraries = [root] if root.tag == 'library' else list(root.iter('library'))
    out = []
    for lib in libraries:
        lib_path = os.path.normpath(os.path.join(base_dir, lib.get('path', '.')))
        for cls in lib.iter('class'):
            base = cls.get('base_class_type', '')
            if base_class_type is not None and base != base_class_type:
                continue
            name = cls.get('name')
            ctype = cls.get('type')
            if not name or not ctype:
                raise PluginXmlError('%s: <class> needs "name" and "type" attributes' % path)
            qtgui = cls.find('qtgui')
            if '::' in ctype or '.' not in ctype:
                module_name, class_attr = None, ctype
                plugin_id = name if '/' in name else '%s/%s' % (package_name, name)
            else:
                module_name, class_attr = ctype.rsplit('.', 1)
                plugin_id = '%s/%s' % (package_name, name)
            groups = []
            if qtgui is not None:
                for g in qtgui.findall('group'):
                    groups.append({'label': _text(g, 'label') or '', 'icon': _icon(g, base_dir),
                                   'statustip': _text(g, 'statustip')})
            out.append({
                'plugin_id': plugin_id,
                'package_name': package_name,
                'class_name': name,
                'class_type': ctype,
                'full_name': ctype.replace('::', '/'),
                'module_name': module_name,
                'class_attr': class_attr,
                'library_path': lib_path,
                'base_class_type': base,
                'plugin_xml': os.path.abspath(path),
                'description': _text(cls, 'description') or '',
                'label': _text(qtgui, 'label') or name,
                'icon': _icon(qtgui, base_dir),
                'statustip': _text(qtgui, 'statustip'),
                'groups': groups,
            })
    return out


def match_plugins(descriptors, pattern):
    """Descriptors matching `pattern` as --standalone does: an exact id/full name, else a
    case-insensitive substring of the plugin id or of the full name."""
    exact = [d for d in descriptors if pattern in (d['plugin_id'], d['full_name'], d['class_type'])]
    if exact:
        return exact
    p = pattern.lower()
    return [d for d in descriptors if p in d['plugin_id'].lower() or p in d['full_name'].lower()]
