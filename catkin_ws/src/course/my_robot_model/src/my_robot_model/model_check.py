"""Checks of an expanded URDF that a simulator and RViz rely on (no ROS master needed).

`problems(xml)` lists, one line each: a link without collision or inertial (except a pure
root frame such as base_footprint), a non-positive mass, an inertia tensor that is not
positive definite or breaks the triangle inequality, joints naming missing links, a link
with two parents or a tree with more than one root, a moving joint without an axis,
a revolute/prismatic joint without limits, undefined materials, unresolvable meshes.
"""
import os
import subprocess
import tempfile
import xml.etree.ElementTree as ET

import numpy as np

MOVING = ('revolute', 'continuous', 'prismatic')


class ModelError(Exception):
    """The text is not a URDF that can be checked at all."""


class Model:
    def __init__(self, root):
        self.name = root.get('name')
        self.links = {l.get('name'): l for l in root.findall('link')}
        self.joints = {j.get('name'): j for j in root.findall('joint')}
        self.materials = {m.get('name'): m for m in root.findall('material')}
        self.transmissions = root.findall('transmission')
        self.gazebo = root.findall('gazebo')
        self.xml = root

    def parent_of(self):
        """{child link: joint element}"""
        return {j.find('child').get('link'): j for j in self.joints.values()
                if j.find('child') is not None}

    def roots(self):
        children = set(self.parent_of())
        return sorted(l for l in self.links if l not in children)

    def root(self):
        roots = self.roots()
        if len(roots) != 1:
            raise ModelError('robot %r has %d root links %s, expected one' % (self.name, len(roots), roots))
        return roots[0]

    def moving_joints(self):
        return sorted(n for n, j in self.joints.items() if j.get('type') in MOVING)


def parse(xml_text):
    try:
        root = ET.fromstring(xml_text)
    except ET.ParseError as e:
        raise ModelError('not well-formed XML: %s' % e)
    if root.tag != 'robot':
        raise ModelError('root element is <%s>, a URDF starts with <robot>' % root.tag)
    return Model(root)


def inertia_matrix(inertial):
    i = inertial.find('inertia')
    if i is None:
        return None
    g = lambda k: float(i.get(k, '0'))   # noqa: E731
    return np.array([[g('ixx'), g('ixy'), g('ixz')],
                     [g('ixy'), g('iyy'), g('iyz')],
                     [g('ixz'), g('iyz'), g('izz')]])


def _floats(text, n, what):
    try:
        v = [float(x) for x in text.split()]
    except (AttributeError, ValueError):
        v = []
    if len(v) != n:
        raise ModelError('%s: expected %d numbers, got %r' % (what, n, text))
    return v


def _inertial_problems(name, inertial):
    out = []
    if inertial is None:
        return ['link %s: no <inertial>' % name]
    mass = inertial.find('mass')
    try:
        m = float(mass.get('value')) if mass is not None else None
    except (TypeError, ValueError):
        m = None
    if m is None or not m > 0:
        out.append('link %s: mass must be a number > 0, got %r'
                   % (name, None if mass is None else mass.get('value')))
    try:
        I = inertia_matrix(inertial)
    except ValueError as e:
        return out + ['link %s: bad inertia value (%s)' % (name, e)]
    if I is None:
        return out + ['link %s: <inertial> without <inertia>' % name]
    ev = np.linalg.eigvalsh(I)
    if not ev.min() > 0:
        out.append('link %s: inertia is not positive definite (principal moments %s)'
                   % (name, ', '.join('%.3g' % e for e in ev)))
    else:
        a, b, c = sorted(ev)
        if a + b < c * (1 - 1e-6):
            out.append('link %s: principal moments %.3g %.3g %.3g break the triangle inequality'
                       % (name, a, b, c))
    return out


def _geometry_problems(where, geom, resolve):
    if geom is None or len(list(geom)) != 1:
        return ['%s: <geometry> must hold exactly one shape' % where]
    shape = list(geom)[0]
    need = {'box': ['size'], 'cylinder': ['radius', 'length'], 'sphere': ['radius'],
            'mesh': ['filename']}.get(shape.tag)
    if need is None:
        return ['%s: unknown shape <%s>' % (where, shape.tag)]
    out = []
    for attr in need:
        if shape.get(attr) is None:
            out.append('%s: <%s> without %s' % (where, shape.tag, attr))
    if shape.tag == 'mesh' and shape.get('filename') and resolve:
        path = resolve(shape.get('filename'))
        if path is None or not os.path.isfile(path):
            out.append('%s: mesh %s not found' % (where, shape.get('filename')))
    elif shape.tag != 'mesh':
        for attr in need:
            try:
                vals = [float(x) for x in (shape.get(attr) or '').split()]
            except ValueError:
                vals = []
            if not vals or min(vals) <= 0:
                out.append('%s: <%s %s="%s"> must be positive' % (where, shape.tag, attr, shape.get(attr)))
    return out


def problems(xml_text, root_frames=('base_footprint',), resolve=None):
    """Every problem found, as one line each ([] for a good model). `root_frames`: links that may
    be bare frames (no geometry, no inertia) when they are the root. `resolve(url)` maps a mesh
    URL to a file path (None: meshes are not looked up)."""
    model = parse(xml_text)
    out = []
    if not model.links:
        return ['robot %r has no links' % model.name]
    seen_child = {}
    for jn, j in model.joints.items():
        parent, child = j.find('parent'), j.find('child')
        if parent is None or child is None:
            out.append('joint %s: needs <parent link> and <child link>' % jn)
            continue
        for role, el in (('parent', parent), ('child', child)):
            if el.get('link') not in model.links:
                out.append('joint %s: %s link %r is not defined' % (jn, role, el.get('link')))
        if child.get('link') in seen_child:
            out.append('link %s: child of two joints (%s, %s)' % (child.get('link'), seen_child[child.get('link')], jn))
        seen_child[child.get('link')] = jn
        jt = j.get('type')
        if jt not in MOVING + ('fixed', 'floating', 'planar'):
            out.append('joint %s: unknown type %r' % (jn, jt))
        if jt in MOVING:
            axis = j.find('axis')
            if axis is None or not np.linalg.norm(_floats(axis.get('xyz'), 3, 'joint %s axis' % jn)) > 0:
                out.append('joint %s: %s joint needs a non-zero <axis xyz>' % (jn, jt))
        if jt in ('revolute', 'prismatic'):
            lim = j.find('limit')
            if lim is None or lim.get('lower') is None or lim.get('upper') is None:
                out.append('joint %s: %s joint needs <limit lower upper effort velocity>' % (jn, jt))
    roots = model.roots()
    if len(roots) != 1:
        out.append('the links form %d trees (roots %s), expected one' % (len(roots), ', '.join(roots)))
    for ln, link in sorted(model.links.items()):
        bare = ln in roots and ln in root_frames
        if bare and not list(link):
            continue
        cols = link.findall('collision')
        if not cols:
            out.append('link %s: no <collision>' % ln)
        for k, c in enumerate(cols):
            out += _geometry_problems('link %s collision %d' % (ln, k), c.find('geometry'), resolve)
        for k, v in enumerate(link.findall('visual')):
            out += _geometry_problems('link %s visual %d' % (ln, k), v.find('geometry'), resolve)
            mat = v.find('material')
            if mat is not None and mat.find('color') is None and mat.find('texture') is None \
                    and mat.get('name') not in model.materials:
                out.append('link %s visual %d: material %r is not defined' % (ln, k, mat.get('name')))
        out += _inertial_problems(ln, link.find('inertial'))
    return out


def material_colours(xml_text):
    """{material name: (r, g, b, a)} of the top-level and inline materials."""
    model = parse(xml_text)
    colours = {}
    for m in model.xml.iter('material'):
        c = m.find('color')
        if c is not None and m.get('name'):
            colours[m.get('name')] = tuple(_floats(c.get('rgba'), 4, 'material %s' % m.get('name')))
    return colours


def package_resolver(find_package):
    """resolve(url) for package:// and file:// URLs, given find_package(name) -> directory."""
    def resolve(url):
        if url.startswith('package://'):
            pkg, _, rest = url[len('package://'):].partition('/')
            try:
                base = find_package(pkg)
            except Exception:
                return None
            return os.path.join(base, rest) if base else None
        if url.startswith('file://'):
            return url[len('file://'):]
        return url
    return resolve


def rospack_resolver():
    import rospkg
    return package_resolver(rospkg.RosPack().get_path)


def check_urdf(xml_text, timeout=30):
    """Run liburdfdom's check_urdf on the text; returns (exit code, output)."""
    with tempfile.NamedTemporaryFile('w', suffix='.urdf', delete=False) as f:
        f.write(xml_text)
        path = f.name
    try:
        r = subprocess.run(['check_urdf', path], capture_output=True, text=True, timeout=timeout)
        return r.returncode, r.stdout + r.stderr
    finally:
        os.unlink(path)


def expand_xacro(path, env=None, args=(), timeout=60):
    """`rosrun xacro xacro PATH [args]` -> URDF text; ModelError with xacro's message on failure."""
    r = subprocess.run(['rosrun', 'xacro', 'xacro', path] + list(args), capture_output=True,
                       text=True, timeout=timeout, env=env)
    if r.returncode != 0:
        raise ModelError('xacro %s failed (%d): %s' % (path, r.returncode, (r.stderr or r.stdout).strip()))
    return r.stdout


def checked_model(path, root=None, root_frames=('base_footprint',)):
    """Expand a robot xacro, require `check_urdf` to pass (and name `root` as the root link
    when given) and the simulator checks (`problems`) to find nothing; return the parsed
    model. AssertionError with check_urdf's output / the problem list otherwise."""
    urdf = expand_xacro(path)
    rc, out = check_urdf(urdf)
    assert rc == 0, out
    if root is not None:
        assert 'root Link: %s' % root in out, out
    found = problems(urdf, root_frames=root_frames, resolve=rospack_resolver())
    assert found == [], found
    return parse(urdf)
