"""Finds plugin.xml files exported by ROS packages (`<export><TAG plugin="${prefix}/plugin.xml"/>`),
and the provider of the Python plugins among them (the original's RospkgPluginProvider)."""
import os
import xml.etree.ElementTree as ET

from qt_gui.plugin_descriptor import PluginXmlError, parse_plugin_xml
from qt_gui.plugin_provider import PythonPluginProvider


def exported_plugin_xmls(package_path, export_tag):
    """plugin.xml paths a package exports under `export_tag` (package.xml, or manifest.xml)."""
    for manifest in ('package.xml', 'manifest.xml'):
        path = os.path.join(package_path, manifest)
        if not os.path.isfile(path):
            continue
        try:
            with open(path, 'rb') as f:
                raw = f.read()
        except OSError:
            return []
        if export_tag.encode() not in raw:
            return []
        root = ET.fromstring(raw)
        out = []
        for export in root.findall('export'):
            for child in export:
                if child.tag == export_tag and child.get('plugin'):
                    out.append(child.get('plugin').replace('${prefix}', package_path))
        return out
    return []


def crawl(rospack, export_tag, base_class_type):
    """(descriptors, error lines) of every package on ROS_PACKAGE_PATH."""
    descriptors, errors = [], []
    for name in sorted(rospack.list()):
        try:
            path = rospack.get_path(name)
            xmls = exported_plugin_xmls(path, export_tag)
        except Exception as e:
            errors.append('RospkgPluginProvider: could not read the manifest of package "%s": %s'
                          % (name, e))
            continue
        for xml_path in xmls:
            try:
                descriptors.extend(parse_plugin_xml(xml_path, name, base_class_type))
            except PluginXmlError as e:
                errors.append('RospkgPluginProvider: %s' % e)
    return descriptors, errors


class RospkgPluginProvider(PythonPluginProvider):
    """The Python classes of base `base_class_type` in the plugin.xml files that the packages on
    ROS_PACKAGE_PATH export under `export_tag` (e.g. 'qt_gui' and 'qt_gui_py::Plugin', or 'rqt_gui'
    and 'rqt_gui_py::PluginProvider' for the providers a RecursivePluginProvider loads)."""

    def __init__(self, export_tag, base_class_type, rospack=None):
        super(RospkgPluginProvider, self).__init__()
        self.export_tag = export_tag
        self.base_class_type = base_class_type
        self._rospack = rospack

    def discover(self):
        if self._rospack is None:
            from rospkg import RosPack
            self._rospack = RosPack()
        descriptors, self.errors = crawl(self._rospack, self.export_tag, self.base_class_type)
        return descriptors
