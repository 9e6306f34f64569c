"""Lab 4's scene: the SDF world's light, ground, gravity and objects (no rospy)."""
import os
import xml.etree.ElementTree as ET

NOT_OBJECTS = ('sun', 'ground_plane')


class SceneError(Exception):
    """The world file cannot be analysed; one line."""


def find_worlds(pkg_dir):
    out = []
    for d, dirs, files in os.walk(pkg_dir):
        dirs[:] = sorted(x for x in dirs if not x.startswith('.') and x not in ('build', 'devel'))
        out += [os.path.join(d, f) for f in sorted(files) if f.endswith(('.world', '.sdf'))
                and 'model.sdf' != f]
    return out


def _local(tag):
    return tag.split('}')[-1] if isinstance(tag, str) else ''


def model_has_mesh(uri, model_dirs):
    """True/False for a model:// URI found in model_dirs, None if not found."""
    name = uri[len('model://'):].strip('/').split('/')[0]
    for d in model_dirs:
        p = os.path.join(d, name, 'model.sdf')
        if os.path.isfile(p):
            with open(p, errors='replace') as f:
                return '<mesh' in f.read()
    return None


def analyse_scene(text):
    """{'light', 'ground', 'gravity', 'objects': [(kind, key, name)], 'names': [...]}"""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise SceneError('not XML: %s' % e)
    world = root if _local(root.tag) == 'world' else next(
        (el for el in root.iter() if _local(el.tag) == 'world'), None)
    if world is None:
        raise SceneError('no <world> element')
    res = {'light': False, 'ground': False, 'gravity': None, 'objects': [], 'names': []}
    for el in world:
        tag = _local(el.tag)
        if tag == 'light':
            res['light'] = True
        elif tag == 'gravity':
            try:
                res['gravity'] = [float(x) for x in (el.text or '').split()]
            except ValueError:
                raise SceneError('<gravity> %r is not 3 numbers' % el.text)
        elif tag == 'include':
            uri = (el.findtext('uri') or '').strip()
            name = (el.findtext('name') or '').strip() or uri.rstrip('/').split('/')[-1]
            res['names'].append(name)
            base = uri[len('model://'):].strip('/').split('/')[0] if uri.startswith('model://') else uri
            if base == 'sun':
                res['light'] = True
            elif base == 'ground_plane':
                res['ground'] = True
            else:
                res['objects'].append(('include', uri, name))
        elif tag == 'model':
            name = el.get('name', '')
            res['names'].append(name)
            geoms = [_local(g.tag) for g in el.iter()
                     if _local(g.tag) in ('mesh', 'plane', 'box', 'sphere', 'cylinder')]
            if 'plane' in geoms:
                res['ground'] = True
            meshes = sorted({(m.findtext('uri') or '').strip() for m in el.iter() if _local(m.tag) == 'mesh'})
            if meshes:
                res['objects'].append(('mesh', ' '.join(meshes), name))
            else:
                res['objects'].append(('primitive', name, name))
    return res


def scene_verdict(scene, model_dirs):
    """(passed, ru, en) of criterion 1."""
    problems = []
    if not scene['light']:
        problems.append(('нет источника света (<light> или model://sun)', 'no light (<light> or model://sun)'))
    if not scene['ground']:
        problems.append(('нет земли (model://ground_plane или <plane>)',
                         'no ground (model://ground_plane or a <plane>)'))
    g = scene['gravity']
    if not g or len(g) != 3 or not g[2] < 0:
        problems.append(('нет <gravity> с z < 0', 'no <gravity> with z < 0'))
    kinds = {}
    prim = []
    for kind, key, name in scene['objects']:
        if kind == 'primitive':
            prim.append(name)
            continue
        if kind == 'include' and key.startswith('model://') and model_has_mesh(key, model_dirs) is False:
            prim.append(name)
            continue
        kinds.setdefault(key, name)
    objs = ', '.join(sorted(kinds.values()))
    if len(kinds) < 3:
        extra_ru = ' (примитивы не считаются: %s)' % ', '.join(prim) if prim else ''
        extra_en = ' (primitives do not count: %s)' % ', '.join(prim) if prim else ''
        problems.append(('разных непримитивных объектов %d (%s), нужно не менее 3%s'
                         % (len(kinds), objs or '—', extra_ru),
                         '%d different non-primitive objects (%s), at least 3 needed%s'
                         % (len(kinds), objs or 'none', extra_en)))
    if problems:
        return False, '; '.join(p[0] for p in problems), '; '.join(p[1] for p in problems)
    return True, 'свет, земля, гравитация %s; объекты: %s' % (' '.join('%g' % x for x in g), objs), \
        'light, ground, gravity %s; objects: %s' % (' '.join('%g' % x for x in g), objs)
