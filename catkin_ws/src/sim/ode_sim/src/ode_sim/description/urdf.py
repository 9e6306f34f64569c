"""URDF (with Gazebo's <gazebo> extensions and <transmission>s) -> the description data model.

Follows what Gazebo classic does when it spawns a URDF (sdformat's URDF->SDF converter):
- links joined by a fixed joint are lumped into their parent (mass, centre of mass and inertia
  combined; collisions, visuals and sensors re-posed) unless the joint's
  <gazebo reference="JOINT"> sets <disableFixedJointLumping> or <preserveFixedJoint>;
- a link without <inertial> that is not lumped is left out, with all links below it (the
  converter's "urdf2sdf: link[NAME] has no inertia, not modeled in sdf"): a warning here;
- a root link named 'world' fixes the model to the world.
Link poses come from forward kinematics at zero joint positions; the model frame is the root
link frame. The lumping and the links and joints it yields: urdf_lump.py. The kinematic tree
(its one root, a loop) is the one urdf_tree.py reads for the model checker and the graders too;
here every element is also read strictly, the first problem being the error.
"""
import math
import os

import numpy as np

from ode_sim.description.model import Collision, Geometry, Inertial, Model, ModelError, Visual
from ode_sim.description.resolve import ModelPaths
from ode_sim.description.sdf_elements import load_mesh_geometry
from ode_sim.description.xmldoc import ParseContext, parse_xml
from ode_sim.description.transforms import Pose
from ode_sim.description.urdf_ext import GazeboExtensions
from ode_sim.description.urdf_lump import FixedJointLumping
from ode_sim.description.urdf_tree import read_tree


class _ULink:
    def __init__(self, name, el):
        self.name = name
        self.el = el
        self.inertial = None
        self.collisions = []        # Collision (pose in this link), urdf name
        self.visuals = []
        self.parent_joint = None
        self.child_joints = []


class _UJoint:
    def __init__(self, name, jtype, el):
        self.name = name
        self.type = jtype
        self.el = el
        self.parent = ''
        self.child = ''
        self.origin = Pose()
        self.axis = np.array([1.0, 0.0, 0.0])
        self.lower = self.upper = self.effort = self.velocity = None
        self.damping = self.friction = 0.0


class _Parser(GazeboExtensions, FixedJointLumping):
    def __init__(self, text, source, model_name, paths):
        self.source = source
        self.doc = parse_xml(text, source)
        self.paths = paths or ModelPaths()
        self.base_dir = os.path.dirname(os.path.abspath(source)) if os.path.exists(source) \
            else os.getcwd()
        self.warnings = []
        self.ctx = ParseContext(self.doc, self.paths, self.base_dir, self.warnings, (1, 6))
        self.model_name = model_name
        self.materials = {}

    # -------------------------------------------------------------------- helpers
    def err(self, el, msg):
        return self.doc.error(el, msg)

    def warn(self, el, msg):
        self.warnings.append('%s: %s' % (self.doc.where(el), msg))

    def attr(self, el, name, what=None):
        v = el.get(name)
        if v is None or not v.strip():
            raise self.err(el, '<%s> needs a %s attribute' % (what or el.tag, name))
        return v.strip()

    def nums(self, el, name, n, default=None, what=None):
        v = el.get(name)
        if v is None or not v.strip():
            if default is None:
                raise self.err(el, '<%s> needs a %s attribute' % (what or el.tag, name))
            return default
        try:
            vals = [float(x) for x in v.split()]
        except ValueError:
            vals = []
        if len(vals) != n or not all(math.isfinite(x) for x in vals):
            raise self.err(el, '<%s %s=%r>: expected %d number%s'
                           % (what or el.tag, name, v, n, 's' if n > 1 else ''))
        return vals if n > 1 else vals[0]

    def origin(self, el):
        o = el.find('origin')
        if o is None:
            return Pose()
        xyz = self.nums(o, 'xyz', 3, [0.0, 0.0, 0.0])
        rpy = self.nums(o, 'rpy', 3, [0.0, 0.0, 0.0])
        return Pose.from_xyz_rpy(xyz, rpy)

    def ext_float(self, el):
        try:
            v = float((el.text or '').strip())
        except ValueError:
            raise self.err(el, '<%s> must be a number, got %r' % (el.tag, (el.text or '').strip()))
        if not math.isfinite(v):
            raise self.err(el, '<%s> must be finite' % el.tag)
        return v

    # -------------------------------------------------------------------- elements
    def geometry(self, owner, link_name, optional_mesh):
        g = owner.find('geometry')
        what = '<%s> of link %r' % (owner.tag, link_name)
        if g is None:
            raise self.err(owner, '%s needs <geometry>' % what)
        shapes = [c for c in g if isinstance(c.tag, str)]
        if not shapes:
            raise self.err(g, '<geometry> of %s is empty' % what)
        s = shapes[0]
        if s.tag == 'box':
            size = self.nums(s, 'size', 3)
            if min(size) <= 0:
                raise self.err(s, '<box size> must be positive in %s' % what)
            return Geometry('box', size=tuple(size))
        if s.tag == 'cylinder':
            r, length = self.nums(s, 'radius', 1), self.nums(s, 'length', 1)
            if r <= 0 or length <= 0:
                raise self.err(s, '<cylinder> radius and length must be positive in %s' % what)
            return Geometry('cylinder', radius=r, length=length)
        if s.tag == 'sphere':
            r = self.nums(s, 'radius', 1)
            if r <= 0:
                raise self.err(s, '<sphere radius> must be positive in %s' % what)
            return Geometry('sphere', radius=r)
        if s.tag == 'mesh':
            uri = self.attr(s, 'filename', 'mesh')
            scale = self.nums(s, 'scale', 3, [1.0, 1.0, 1.0])
            return load_mesh_geometry(self.ctx, s, uri, scale, optional_mesh)
        raise self.err(s, '<%s> geometry is not supported in %s (box, cylinder, sphere, mesh)'
                       % (s.tag, what))

    def material_color(self, mat, link_name):
        """RGBA of a visual's <material>, or None."""
        if mat is None:
            return None
        name = (mat.get('name') or '').strip()
        c = mat.find('color')
        if c is not None:
            rgba = tuple(self.nums(c, 'rgba', 4))
            if name and name not in self.materials:
                self.materials[name] = rgba
            return rgba
        if name in self.materials:
            return self.materials[name]
        if mat.find('texture') is not None:
            return None
        if name:
            raise self.err(mat, "link '%s' material '%s' undefined: define <material name=%r> "
                                "with <color rgba=...> at the robot level"
                           % (link_name, name, name))
        return None

    def parse_link(self, el):
        name = self.attr(el, 'name', 'link')
        ul = _ULink(name, el)
        ine = el.find('inertial')
        if ine is not None:
            m = ine.find('mass')
            if m is None:
                raise self.err(ine, "<inertial> of link '%s' needs <mass value=...>" % name)
            mass = self.nums(m, 'value', 1, what='mass')
            inertial = Inertial(mass=mass, pose=self.origin(ine))
            ia = ine.find('inertia')
            if ia is None:
                raise self.err(ine, "<inertial> of link '%s' needs <inertia ixx= ixy= ixz= iyy= "
                                    "iyz= izz=>" % name)
            for k in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz'):
                setattr(inertial, k, self.nums(ia, k, 1, what='inertia'))
            ul.inertial = inertial
        for c in el.findall('collision'):
            geom = self.geometry(c, name, optional_mesh=False)
            ul.collisions.append((Collision(name=(c.get('name') or '').strip(), geometry=geom,
                                            pose=self.origin(c)), name))
        for v in el.findall('visual'):
            geom = self.geometry(v, name, optional_mesh=True)
            color = self.material_color(v.find('material'), name)
            if geom is None:
                continue
            vis = Visual(name=(v.get('name') or '').strip(), geometry=geom, pose=self.origin(v))
            if color is not None:
                vis.color = color
            ul.visuals.append((vis, name))
        return ul

    def parse_joint(self, el, links):
        name = self.attr(el, 'name', 'joint')
        jtype = self.attr(el, 'type', 'joint name=%r' % name)
        if jtype in ('floating', 'planar'):
            raise self.err(el, "joint '%s' of type %s is not supported (revolute, continuous, "
                               "prismatic, fixed)" % (name, jtype))
        if jtype not in ('revolute', 'continuous', 'prismatic', 'fixed'):
            raise self.err(el, "joint '%s' has unknown type %r" % (name, jtype))
        j = _UJoint(name, jtype, el)
        for tag in ('parent', 'child'):
            t = el.find(tag)
            if t is None:
                raise self.err(el, "joint '%s' needs <%s link=...>" % (name, tag))
            ln = self.attr(t, 'link', tag)
            if ln not in links:
                raise self.err(t, "joint '%s' refers to unknown link '%s'" % (name, ln))
            setattr(j, tag, ln)
        if j.parent == j.child:
            raise self.err(el, "joint '%s': parent and child are the same link" % name)
        j.origin = self.origin(el)
        ax = el.find('axis')
        if ax is not None and jtype != 'fixed':
            a = np.array(self.nums(ax, 'xyz', 3, [1.0, 0.0, 0.0]))
            n = np.linalg.norm(a)
            if n == 0:
                raise self.err(ax, "joint '%s': <axis xyz> must not be zero" % name)
            j.axis = a / n
        lim = el.find('limit')
        if lim is not None:
            j.effort = self.nums(lim, 'effort', 1, what='limit')
            j.velocity = self.nums(lim, 'velocity', 1, what='limit')
            if jtype in ('revolute', 'prismatic'):
                j.lower = self.nums(lim, 'lower', 1, 0.0)
                j.upper = self.nums(lim, 'upper', 1, 0.0)
                if j.lower > j.upper:
                    self.warn(lim, "joint '%s': lower limit %g > upper %g, swapped (as Gazebo "
                                   "does)" % (name, j.lower, j.upper))
                    j.lower, j.upper = j.upper, j.lower
        elif jtype in ('revolute', 'prismatic'):
            raise self.err(el, "joint '%s' is of type %s but has no <limit lower= upper= "
                               "effort= velocity=>" % (name, jtype))
        dyn = el.find('dynamics')
        if dyn is not None:
            j.damping = self.nums(dyn, 'damping', 1, 0.0)
            j.friction = self.nums(dyn, 'friction', 1, 0.0)
        if el.find('mimic') is not None:
            self.warn(el.find('mimic'), "joint '%s': <mimic> is ignored (the joint moves on its "
                                        "own)" % name)
        return j

    # -------------------------------------------------------------------- main
    def parse_links_and_joints(self, root):
        """(links, document order of the links, joints) read strictly: the first problem is a
        one-line error at its element."""
        links = {}
        order = []
        for el in root.findall('link'):
            ul = self.parse_link(el)
            if ul.name in links:
                raise self.err(el, "two links named '%s'" % ul.name)
            links[ul.name] = ul
            order.append(ul.name)
        if not links:
            raise self.err(root, 'the robot has no <link>')
        joints = {}
        for el in root.findall('joint'):
            j = self.parse_joint(el, links)
            if j.name in joints:
                raise self.err(el, "two joints named '%s'" % j.name)
            child = links[j.child]
            if child.parent_joint is not None:
                raise self.err(el, "link '%s' has two parent joints '%s' and '%s'"
                               % (j.child, child.parent_joint.name, j.name))
            child.parent_joint = j
            links[j.parent].child_joints.append(j)
            joints[j.name] = j
        return links, order, joints

    def root_link(self, root, links):
        """The name of the one root link: the kinematic tree as urdf_tree reads it, a one-line
        error for more roots than one or a loop."""
        tree = read_tree(root)
        roots = tree.roots()
        if len(roots) > 1:
            raise self.err(root, 'the robot has %d root links (%s): every link but one needs a '
                                 'parent joint' % (len(roots), ', '.join(repr(r) for r in roots)))
        if not roots:
            raise self.err(root, 'the joints form a loop: no root link')
        if tree.loop:
            joint = links[tree.loop[0]].parent_joint
            raise self.err(joint.el, "the joints form a loop through link '%s' (joint '%s')"
                           % (tree.loop[0], joint.name))
        return roots[0]

    def parse(self):
        root = self.doc.root
        if root.tag != 'robot':
            raise self.err(root, 'expected <robot> as the root element, got <%s>' % root.tag)
        for el in root.iter():
            if isinstance(el.tag, str) and el.tag.startswith('xacro:'):
                raise self.err(el, '<%s> found: this is a xacro file, expand it with xacro '
                                   'first' % el.tag)
        robot_name = (root.get('name') or '').strip()
        if not robot_name:
            raise self.err(root, '<robot> needs a name attribute')
        for m in root.findall('material'):
            name = self.attr(m, 'name', 'material')
            c = m.find('color')
            if c is not None:
                self.materials[name] = tuple(self.nums(c, 'rgba', 4))

        links, order, joints = self.parse_links_and_joints(root)
        root_name = self.root_link(root, links)

        model = Model(name=self.model_name or robot_name, source=self.source)
        # an <origin> right under <robot> (not in the URDF spec; gazebo_ros' updateURDFModelPose
        # writes one and sdformat's URDF parser takes it as the model pose): the model's own
        # pose, composed with a spawn's initial pose (spawning.spawn_pose); identity without
        model.pose = self.origin(root)
        link_ext, joint_ext = self.parse_gazebo(root, links, joints, model)
        self.build(model, links, joints, root_name, order, link_ext, joint_ext)
        self.parse_transmissions(root, model, joints)
        model.warnings = self.warnings
        return model


def parse_urdf(text, source, model_name, paths=None):
    """Model from URDF text. `source` names the file (or parameter) in messages and is the base
    for relative mesh file names; `model_name` names the model (the robot name if empty)."""
    p = _Parser(text, source, model_name, paths)
    p.doc_text = text.decode('utf-8', 'replace') if isinstance(text, bytes) else text
    return p.parse()


def load_urdf(path, model_name, paths=None):
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except OSError as e:
        raise ModelError('%s: cannot read URDF file: %s' % (path, e.strerror or e))
    return parse_urdf(data, path, model_name, paths)
