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

import numpy as np

from ode_sim.description import urdf_tree

MOVING = urdf_tree.MOVING


class ModelError(Exception):
    """The text is not a URDF that can be checked at all."""


class Model:
    """A URDF read by ode_sim.description.urdf_tree (`tree`), with its elements by name for the
    checks and the description packages' tests."""

    def __init__(self, root):
        self.tree = urdf_tree.read_tree(root)
        self.name = self.tree.name
        self.links = {n: l.el for n, l in self.tree.links.items()}
        self.joints = {n: j.el for n, j in self.tree.joints.items()}
        self.materials = {n: m.el for n, m in self.tree.materials.items()}
        self.transmissions = root.findall('transmission')
        self.gazebo = root.findall('gazebo')
        self.xml = root

    def parent_of(self):
        """{child link: joint element}"""
        return {j.child: j.el for j in self.tree.joints.values() if j.child_el is not None}

    def roots(self):
        return sorted(self.tree.roots())

    def root(self):
        roots = self.roots()
        if len(roots) != 1:
            raise ModelError('robot %r has %d root links %s, expected one' % (self.name, len(roots), roots))
        return roots[0]

    def moving_joints(self):
        return sorted(n for n, j in self.tree.joints.items() if j.type in MOVING)


def parse(xml_text):
    try:
        return Model(urdf_tree.parse_robot(xml_text))
    except urdf_tree.NotUrdf as e:
        if e.kind == 'xml':
            raise ModelError('not well-formed XML: %s' % e.detail)
        raise ModelError('root element is <%s>, a URDF starts with <robot>' % e.detail)


def inertia_matrix(inertial):
    i = inertial.find('inertia')
    if i is None:
        return None
    g = lambda k: float(i.get(k, '0'))   # noqa: E731
    return np.array([[g('ixx'), g('ixy'), g('ixz')],
                     [g('ixy'), g('iyy'), g('iyz')],
                     [g('ixz'), g('iyz'), g('izz')]])


def _floats(text, n, what):
    v = urdf_tree.floats(text, n)
    if v is None:
        raise ModelError('%s: expected %d numbers, got %r' % (what, n, text))
    return v


def _inertial_problems(name, inertial):
    """Problems of a link's urdf_tree.Inertial (None: the link has none)."""
    out = []
    if inertial is None:
        return ['link %s: no <inertial>' % name]
    if inertial.mass is None or not inertial.mass > 0:
        out.append('link %s: mass must be a number > 0, got %r'
                   % (name, None if inertial.mass_el is None else inertial.mass_el.get('value')))
    try:
        I = inertia_matrix(inertial.el)
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


def _geometry_problems(where, shape, resolve):
    """Problems of a urdf_tree.Shape (a collision or a visual)."""
    if len(shape.shapes) != 1:
        return ['%s: <geometry> must hold exactly one shape' % where]
    need = urdf_tree.SHAPE_ATTRS.get(shape.kind)
    if need is None:
        return ['%s: unknown shape <%s>' % (where, shape.kind)]
    out = []
    for attr in need:
        if shape.attrs.get(attr) is None:
            out.append('%s: <%s> without %s' % (where, shape.kind, attr))
    if shape.kind == 'mesh' and shape.attrs.get('filename') and resolve:
        path = resolve(shape.attrs['filename'])
        if path is None or not os.path.isfile(path):
            out.append('%s: mesh %s not found' % (where, shape.attrs['filename']))
    elif shape.kind != 'mesh':
        for attr in need:
            vals = shape.values[attr]
            if not vals or min(vals) <= 0:
                out.append('%s: <%s %s="%s"> must be positive' % (where, shape.kind, attr, shape.attrs.get(attr)))
    return out


def _joint_problems(j):
    """A connected joint's axis and limits (urdf_tree.Joint)."""
    out = []
    if j.type in MOVING:
        if j.axis_el is not None and j.axis is None:
            raise ModelError('joint %s axis: expected 3 numbers, got %r' % (j.name, j.axis_el.get('xyz')))
        if j.axis is None or not np.linalg.norm(j.axis) > 0:
            out.append('joint %s: %s joint needs a non-zero <axis xyz>' % (j.name, j.type))
    if j.type in ('revolute', 'prismatic'):
        if j.limit is None or j.limit['lower'] is None or j.limit['upper'] is None:
            out.append('joint %s: %s joint needs <limit lower upper effort velocity>' % (j.name, j.type))
    return out


def _link_problems(tree, link, resolve):
    out = []
    if not link.collisions:
        out.append('link %s: no <collision>' % link.name)
    for k, c in enumerate(link.collisions):
        out += _geometry_problems('link %s collision %d' % (link.name, k), c, resolve)
    for k, v in enumerate(link.visuals):
        out += _geometry_problems('link %s visual %d' % (link.name, k), v, resolve)
        mat = v.material
        if mat is not None and mat.color_el is None and mat.texture_el is None \
                and mat.name not in tree.materials:
            out.append('link %s visual %d: material %r is not defined' % (link.name, k, mat.el.get('name')))
    return out + _inertial_problems(link.name, link.inertial)


def problems(xml_text, root_frames=('base_footprint',), resolve=None):
    """Every problem found, as one line each ([] for a good model). `root_frames`: links that may
    be bare frames (no geometry, no inertia) when they are the root. `resolve(url)` maps a mesh
    URL to a file path (None: meshes are not looked up)."""
    tree = parse(xml_text).tree
    if not tree.links:
        return ['robot %r has no links' % tree.name]
    out = []
    for j in tree.joints.values():
        out += j.problems
        if j.connects:
            out += _joint_problems(j)
    out += tree.tree_problems
    roots = tree.roots()
    for ln, link in sorted(tree.links.items()):
        if ln in roots and ln in root_frames and not list(link.el):
            continue        # a bare root frame
        out += _link_problems(tree, link, resolve)
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
