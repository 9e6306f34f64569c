"""The kinematic tree of a URDF as plain data: the one reader of a URDF's links and joints
(standard library only: no ROS, no numpy).

`parse_robot(text)` gives the <robot> element (NotUrdf when the text is not XML or not a
robot); `read_tree(robot)` gives a UrdfTree: links and joints by name in document order, each
with its element, origin, shapes, inertial, axis, limits and mimic, parent and child links.
Nothing is lumped (ode_sim.description.urdf lumps fixed joints for physics) and reading never
stops at the first problem: a number that cannot be read is None (the element keeps the text),
and `tree.problems` lists, one line each, what keeps the links and joints from being one tree
(a joint without parent or child, naming an undefined link, a link with two parents, an
unknown joint type, duplicate names, not exactly one root, a loop). The model checker
(my_robot_model.model_check), the graders (labs/grading/urdf.py) and ode_sim's URDF loader
read URDF through this module.
"""
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Optional

MOVING = ('revolute', 'continuous', 'prismatic')
JOINT_TYPES = MOVING + ('fixed', 'floating', 'planar')
SHAPE_ATTRS = {'box': ('size',), 'cylinder': ('radius', 'length'), 'sphere': ('radius',),
               'mesh': ('filename',)}
INERTIA = ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')
LIMIT = ('lower', 'upper', 'effort', 'velocity')


class NotUrdf(Exception):
    """The text is not XML (`kind` 'xml', `detail` the parser's message) or its root element
    is not <robot> (`kind` 'root', `detail` the root's tag)."""

    def __init__(self, kind, detail):
        super().__init__('not XML: %s' % detail if kind == 'xml'
                         else 'the root element is <%s>, not <robot>' % detail)
        self.kind = kind
        self.detail = detail


def floats(text, n=None):
    """The numbers of an attribute's text ('0 0.1 2'), or None when the text is missing, is not
    numbers or (with `n`) is not `n` of them."""
    try:
        vals = [float(x) for x in text.split()]
    except (AttributeError, ValueError):
        return None
    if not vals or (n is not None and len(vals) != n):
        return None
    return vals


def number(text):
    """One number of an attribute's text, or None."""
    v = floats(text, 1)
    return None if v is None else v[0]


@dataclass
class Origin:
    """An <origin>: xyz and rpy (zeros when left out, None when not 3 numbers)."""
    el: Optional[ET.Element] = None
    xyz: Optional[List[float]] = field(default_factory=lambda: [0.0, 0.0, 0.0])
    rpy: Optional[List[float]] = field(default_factory=lambda: [0.0, 0.0, 0.0])


@dataclass
class Material:
    """A <material>: name (stripped), colour (None without <color> or when not 4 numbers)."""
    el: ET.Element
    name: str = ''
    color_el: Optional[ET.Element] = None
    rgba: Optional[List[float]] = None
    texture_el: Optional[ET.Element] = None


@dataclass
class Shape:
    """A <collision> or <visual>: its geometry's first shape (`kind` its tag, None without
    <geometry> or with an empty one), the shape's attributes as written and their numbers."""
    el: ET.Element
    name: str = ''
    origin: Origin = field(default_factory=Origin)
    geometry_el: Optional[ET.Element] = None
    shapes: List[ET.Element] = field(default_factory=list)   # every child of <geometry>
    kind: Optional[str] = None
    attrs: Dict[str, str] = field(default_factory=dict)
    values: Dict[str, Optional[List[float]]] = field(default_factory=dict)
    material: Optional[Material] = None                        # visuals only


@dataclass
class Inertial:
    """An <inertial>: mass and the six inertia values (None when missing or not a number)."""
    el: ET.Element
    origin: Origin = field(default_factory=Origin)
    mass_el: Optional[ET.Element] = None
    mass: Optional[float] = None
    inertia_el: Optional[ET.Element] = None
    inertia: Dict[str, Optional[float]] = field(default_factory=dict)


@dataclass
class Link:
    el: ET.Element
    name: str
    collisions: List[Shape] = field(default_factory=list)
    visuals: List[Shape] = field(default_factory=list)
    inertial: Optional[Inertial] = None
    parent_joint: Optional[str] = None      # the (first) joint whose child this link is
    child_joints: List[str] = field(default_factory=list)


@dataclass
class Joint:
    el: ET.Element
    name: str
    type: Optional[str] = None
    parent_el: Optional[ET.Element] = None
    child_el: Optional[ET.Element] = None
    parent: Optional[str] = None            # link names as written (None: no link attribute)
    child: Optional[str] = None
    origin: Origin = field(default_factory=Origin)
    axis_el: Optional[ET.Element] = None
    axis: Optional[List[float]] = None      # as written; None without <axis> or not 3 numbers
    limit_el: Optional[ET.Element] = None
    limit: Optional[Dict[str, Optional[float]]] = None    # lower upper effort velocity
    dynamics_el: Optional[ET.Element] = None
    mimic_el: Optional[ET.Element] = None
    problems: List[str] = field(default_factory=list)    # this joint's share of tree.problems

    @property
    def connects(self):
        """Both <parent> and <child> are there."""
        return self.parent_el is not None and self.child_el is not None


@dataclass
class UrdfTree:
    el: ET.Element
    name: Optional[str]
    links: Dict[str, Link] = field(default_factory=dict)
    joints: Dict[str, Joint] = field(default_factory=dict)
    materials: Dict[str, Material] = field(default_factory=dict)   # the robot-level ones
    duplicates: List[ET.Element] = field(default_factory=list)     # links/joints named again
    loop: List[str] = field(default_factory=list)   # links not reached from the root
    tree_problems: List[str] = field(default_factory=list)

    @property
    def problems(self):
        """Every problem: the joints' (in document order), then the tree's."""
        return [p for j in self.joints.values() for p in j.problems] + self.tree_problems

    def children(self):
        """The links that are the child of some joint."""
        return {j.child for j in self.joints.values() if j.child_el is not None}

    def roots(self):
        """The links that are nobody's child, in document order."""
        kids = self.children()
        return [n for n in self.links if n not in kids]


def parse_robot(text):
    """The <robot> element of a URDF text (str or bytes); NotUrdf otherwise."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise NotUrdf('xml', e)
    if root.tag != 'robot':
        raise NotUrdf('root', root.tag)
    return root


def read_origin(owner):
    o = owner.find('origin')
    if o is None:
        return Origin()
    return Origin(o, *[floats(o.get(k), 3) if o.get(k) else [0.0, 0.0, 0.0] for k in ('xyz', 'rpy')])


def read_material(m):
    if m is None:
        return None
    c = m.find('color')
    return Material(m, (m.get('name') or '').strip(), c,
                    floats(c.get('rgba'), 4) if c is not None else None, m.find('texture'))


def read_shape(el):
    s = Shape(el, (el.get('name') or '').strip(), read_origin(el), el.find('geometry'))
    if s.geometry_el is not None:
        s.shapes = list(s.geometry_el)
    if s.shapes:
        first = s.shapes[0]
        s.kind, s.attrs = first.tag, dict(first.attrib)
        for a in SHAPE_ATTRS.get(first.tag, ()):
            if a != 'filename':
                s.values[a] = floats(first.get(a))
    if el.tag == 'visual':
        s.material = read_material(el.find('material'))
    return s


def read_inertial(el):
    if el is None:
        return None
    i = Inertial(el, read_origin(el), el.find('mass'))
    if i.mass_el is not None:
        i.mass = number(i.mass_el.get('value'))
    i.inertia_el = el.find('inertia')
    if i.inertia_el is not None:
        i.inertia = {k: number(i.inertia_el.get(k)) for k in INERTIA}
    return i


def read_link(el):
    return Link(el, el.get('name'), [read_shape(c) for c in el.findall('collision')],
                [read_shape(v) for v in el.findall('visual')], read_inertial(el.find('inertial')))


def read_joint(el):
    j = Joint(el, el.get('name'), el.get('type'), el.find('parent'), el.find('child'))
    j.parent = j.parent_el.get('link') if j.parent_el is not None else None
    j.child = j.child_el.get('link') if j.child_el is not None else None
    j.origin = read_origin(el)
    j.axis_el, j.limit_el = el.find('axis'), el.find('limit')
    if j.axis_el is not None:
        j.axis = floats(j.axis_el.get('xyz'), 3)
    if j.limit_el is not None:
        j.limit = {k: number(j.limit_el.get(k)) for k in LIMIT}
    j.dynamics_el, j.mimic_el = el.find('dynamics'), el.find('mimic')
    return j


def _connect(tree):
    """Parent and child links of every joint, and the joints' problems."""
    seen = {}                               # child link: the last joint naming it
    for j in tree.joints.values():
        if not j.connects:
            j.problems.append('joint %s: needs <parent link> and <child link>' % j.name)
            continue
        for role, name in (('parent', j.parent), ('child', j.child)):
            if name not in tree.links:
                j.problems.append('joint %s: %s link %r is not defined' % (j.name, role, name))
        if j.child in seen:
            j.problems.append('link %s: child of two joints (%s, %s)' % (j.child, seen[j.child], j.name))
        elif j.child in tree.links:
            tree.links[j.child].parent_joint = j.name
        seen[j.child] = j.name
        if j.parent in tree.links:
            tree.links[j.parent].child_joints.append(j.name)
        if j.type not in JOINT_TYPES:
            j.problems.append('joint %s: unknown type %r' % (j.name, j.type))


def _check_tree(tree):
    """The tree's own problems: duplicate names, not one root, links not reached (a loop)."""
    for el in tree.duplicates:
        tree.tree_problems.append('two %ss named %s' % (el.tag, el.get('name')))
    roots = tree.roots()
    if len(roots) != 1:
        tree.tree_problems.append('the links form %d trees (roots %s), expected one'
                                  % (len(roots), ', '.join(sorted(roots))))
    reached, todo = set(), list(roots)
    while todo:
        n = todo.pop()
        reached.add(n)
        todo += [tree.joints[c].child for c in tree.links[n].child_joints
                 if tree.joints[c].child in tree.links and tree.joints[c].child not in reached]
    tree.loop = [n for n in tree.links if n not in reached]
    if tree.loop:
        tree.tree_problems.append('the joints form a loop through link %s (joint %s)'
                                  % (tree.loop[0], tree.links[tree.loop[0]].parent_joint))


def read_tree(robot):
    """UrdfTree of a <robot> element (from parse_robot or any ElementTree parser)."""
    tree = UrdfTree(robot, robot.get('name'))
    for m in robot.findall('material'):
        mat = read_material(m)
        tree.materials[mat.name] = mat
    for tag, table, read in (('link', tree.links, read_link), ('joint', tree.joints, read_joint)):
        for el in robot.findall(tag):
            if el.get('name') in table:
                tree.duplicates.append(el)
            else:
                table[el.get('name')] = read(el)
    _connect(tree)
    _check_tree(tree)
    return tree


def read_urdf(text):
    """read_tree(parse_robot(text))."""
    return read_tree(parse_robot(text))
