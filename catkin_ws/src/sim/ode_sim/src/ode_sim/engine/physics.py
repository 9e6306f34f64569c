"""The physics world: model descriptions (ode_sim.description.model) become ODE bodies, geoms and joints.

Conventions as Gazebo classic on ODE:
- one ODE body per link, placed at the link's centre of mass (ODE needs the mass centre at the
  body origin); geoms hang off the body with an offset, so the link frame is recovered exactly;
- links of one model do not collide with each other unless the link has self_collide;
- contact parameters combine the two surfaces: mu = min, kp in series, kd summed, turned into
  ODE's soft ERP/CFM for the step size; friction pyramid (dContactApprox1) as Gazebo's default;
- joints attach (child, parent) as Gazebo does, so angles, rates and efforts are the child's
  motion relative to the parent about/along the axis;
- joint damping is a torque -d*qdot, joint friction a zero-velocity motor limited to the
  friction value (used only while no velocity/position command drives the joint);
- static models (and the plane) have geoms without bodies.

No ROS here: the node (ode_sim.ros.node) owns time pacing, plugins and the ROS API.
"""
import ctypes
import math

import numpy as np
import ode

from ode_sim.description.model import Geometry, ModelError
from ode_sim.engine.scene import ShapeInstance
from ode_sim.description.transforms import Pose, quat_from_axis_angle, quat_to_matrix

ENV = ode.environment

# Joint parameter numbers of the ODE library actually linked (libode 0.16): PyODE 1.2 still
# exports the pre-0.13 numbering (ode.ParamFMax == 3, which is dParamLoVel in 0.16), so setting
# a motor's force through ode.ParamFMax silently does nothing. These are dParam* of 0.16.
P_LO_STOP, P_HI_STOP, P_VEL, P_LO_VEL, P_HI_VEL, P_FMAX = 0, 1, 2, 3, 4, 5

# ODE worlds, spaces and joint groups are never freed. PyODE's objects clear their references
# in arbitrary order when the garbage collector breaks a cycle (or the interpreter exits), so a
# world could be destroyed before its bodies (dBodyDestroy on freed memory: segfault). Bodies,
# joints and geoms are still freed; only these small containers stay, one set per PhysicsWorld.


def _keep_alive(*objs):
    for obj in objs:
        ctypes.pythonapi.Py_IncRef(ctypes.py_object(obj))


def _ode_q(q):
    """(x, y, z, w) -> ODE's (w, x, y, z)."""
    return (q[3], q[0], q[1], q[2])


def _ros_q(q):
    return (q[1], q[2], q[3], q[0])


class SimLink:
    """A link of a simulated model. Static links have no body."""

    def __init__(self, model, desc, body, com, static_pose=None):
        self.model = model
        self.name = desc.name
        self.desc = desc
        self.body = body
        self.com = com                  # Pose of the COM (body) frame in the link frame
        self._com_inv = com.inverse()
        self._static_pose = static_pose
        self.geoms = []
        self.prev_vel = None            # for acceleration tracking
        self.accel = np.zeros(3)

    def pose(self):
        """The link frame in the world."""
        if self.body is None:
            return self._static_pose
        b = self.body
        return Pose(b.getPosition(), _ros_q(b.getQuaternion())) * self._com_inv

    def frame_pose(self, name):
        """A frame lumped into this link (URDF fixed joint) or the link itself, in the world."""
        if name == self.name or name not in self.desc.lumped:
            return self.pose()
        return self.pose() * self.desc.lumped[name]

    def velocity(self, point=None):
        """(linear velocity of `point` (world; default the link origin), angular velocity),
        both in the world frame."""
        if self.body is None:
            return np.zeros(3), np.zeros(3)
        if point is None:
            point = self.pose().p
        return (np.array(self.body.getPointVel(tuple(point))),
                np.array(self.body.getAngularVel()))

    def wake(self):
        if self.body is not None:
            self.model.world._rouse(self.model.space)
            self.body.enable()

    def add_force(self, force, point=None):
        if self.body is not None:
            self.wake()
            if point is None:
                self.body.addForce(tuple(force))
            else:
                self.body.addForceAtPos(tuple(force), tuple(point))

    def add_torque(self, torque):
        if self.body is not None:
            self.wake()
            self.body.addTorque(tuple(torque))

    def set_state(self, pose, linear, angular):
        """Move the link frame to `pose` (world) with this world twist of its COM; wakes it."""
        if self.body is None:
            return
        target = pose * self.com
        self.wake()
        self.body.setPosition(tuple(float(v) for v in target.p))
        self.body.setQuaternion(_ode_q(target.q))
        self.body.setLinearVel(tuple(float(v) for v in linear))
        self.body.setAngularVel(tuple(float(v) for v in angular))


class SimJoint:
    """A joint between two links (or a link and the world)."""

    def __init__(self, model, desc, joint, parent, child):
        self.model = model
        self.name = desc.name
        self.desc = desc
        self.type = desc.type
        self.joint = joint
        self.parent = parent            # SimLink or None (world)
        self.child = child
        self.effort_cmd = 0.0           # applied every step
        self.vel_cmd = None             # (velocity, fmax) motor target, or None
        self.pos_cmd = None             # position target (servoed by the motor), or None
        self._applied = 0.0             # effort added by torque this step (not in feedback)
        self.active = bool(desc.damping)
        self.world_ref = model.world
        self.limit_effort = desc.effort if desc.effort and desc.effort > 0 else None
        self.limit_velocity = desc.velocity if desc.velocity and desc.velocity > 0 else None

    @property
    def hinge(self):
        return self.type in ('revolute', 'continuous')

    @property
    def slider(self):
        return self.type == 'prismatic'

    def position(self):
        if self.hinge:
            return self.joint.getAngle()
        if self.slider:
            return self.joint.getPosition()
        return 0.0

    def velocity(self):
        if self.hinge:
            return self.joint.getAngleRate()
        if self.slider:
            return self.joint.getPositionRate()
        return 0.0

    def effort(self):
        """The effort the joint applied to its child in the last step about/along the axis
        (command, motor, limits and damping: the constraint feedback)."""
        if not (self.hinge or self.slider):
            return 0.0
        fb = self.joint.getFeedback()
        if fb is None:
            return 0.0
        ax = self.joint.getAxis()
        v = fb[1] if self.hinge else fb[0]
        return v[0] * ax[0] + v[1] * ax[1] + v[2] * ax[2] + self._applied

    def add_effort(self, effort):
        """Add a torque (hinge) or force (slider) along the axis for the next step."""
        if self.hinge:
            self.joint.addTorque(float(effort))
        elif self.slider:
            self.joint.addForce(float(effort))

    def _motor(self, vel, fmax):
        self.joint.setParam(P_VEL, vel)
        self.joint.setParam(P_FMAX, fmax)

    def _idle_motor(self):
        """No command: the motor holds zero velocity with the joint's friction (or is off)."""
        if self.desc.friction > 0:
            self._motor(0.0, self.desc.friction)
        else:
            self.joint.setParam(P_FMAX, 0.0)

    def _update_active(self):
        self.active = bool(self.pos_cmd is not None or self.effort_cmd or self.desc.damping)
        self.world_ref._refresh_active()

    def set_effort(self, effort):
        """Apply this effort every step until changed (clamped to the URDF effort limit)."""
        self.vel_cmd = None
        self.pos_cmd = None
        if self.limit_effort is not None:
            effort = max(-self.limit_effort, min(self.limit_effort, effort))
        self.effort_cmd = float(effort)
        if self.hinge or self.slider:
            self._idle_motor()
        self._update_active()

    def set_velocity(self, velocity, fmax=None):
        """Drive the joint at `velocity` with at most `fmax` (default: the effort limit, else
        a large force), as Gazebo's SetParam("vel") / SetParam("fmax")."""
        if fmax is None:
            fmax = self.limit_effort if self.limit_effort is not None else 1e6
        self.pos_cmd = None
        self.effort_cmd = 0.0
        self.vel_cmd = (float(velocity), float(fmax))
        if self.hinge or self.slider:
            self._motor(self.vel_cmd[0], self.vel_cmd[1])
            self.child.wake()
        self._update_active()

    def set_position_target(self, position):
        """Servo to `position` with the joint motor (effort and velocity limits honoured)."""
        self.vel_cmd = None
        self.effort_cmd = 0.0
        self.pos_cmd = float(position)
        self.child.wake()
        self._update_active()

    def release(self):
        self.vel_cmd = None
        self.pos_cmd = None
        self.effort_cmd = 0.0
        if self.hinge or self.slider:
            self._idle_motor()
        self._update_active()

    def _pre_step(self, dt):
        """Per-step work of an active joint: position servo, effort command, damping."""
        j = self.joint
        if self.pos_cmd is not None:
            vel = (self.pos_cmd - self.position()) / dt
            vmax = self.limit_velocity
            if vmax is not None:
                vel = max(-vmax, min(vmax, vel))
            self._motor(vel, self.limit_effort if self.limit_effort is not None else 1e6)
        effort = self.effort_cmd
        if self.desc.damping:
            effort -= self.desc.damping * self.velocity()
        self._applied = effort
        if effort:
            if self.hinge:
                j.addTorque(effort)
            else:
                j.addForce(effort)


class SimModel:
    def __init__(self, world, desc):
        self.world = world
        self.name = desc.name
        self.desc = desc
        self.static = desc.static
        self.links = {}
        self.joints = {}
        self.space = None
        self.initial_pose = desc.pose.copy()
        self.canonical = None           # SimLink whose pose is the model pose

    def pose(self):
        """The model pose in the world (the canonical link's frame composed with its pose in the
        model, so a freshly spawned model reports its spawn pose)."""
        if self.canonical is None:
            return self.initial_pose
        return self.canonical.pose() * self.canonical.desc.pose.inverse()

    def twist(self):
        """(linear, angular) world velocity of the model frame origin."""
        if self.canonical is None or self.canonical.body is None:
            return np.zeros(3), np.zeros(3)
        return self.canonical.velocity(self.pose().p)

    def bodies(self):
        return [l.body for l in self.links.values() if l.body is not None]

    def wake(self):
        """Wake every body (after a teleport, a push, a reset)."""
        if not self.static:
            self.world._rouse(self.space)
            for b in self.bodies():
                b.enable()

    def set_pose(self, pose):
        """Move the whole model rigidly so that its pose becomes `pose`."""
        if self.static:
            return
        self.wake()
        delta = pose * self.pose().inverse()
        for link in self.links.values():
            b = link.body
            if b is None:
                continue
            bp = delta * Pose(b.getPosition(), _ros_q(b.getQuaternion()))
            b.setPosition(tuple(bp.p))
            b.setQuaternion(_ode_q(bp.q))
            b.enable()

    def set_twist(self, linear, angular):
        """Give every body the rigid-body velocity of the model frame moving at (linear, angular)."""
        self.wake()
        origin = self.pose().p
        lin = np.asarray(linear, dtype=float)
        ang = np.asarray(angular, dtype=float)
        for b in self.bodies():
            r = np.array(b.getPosition()) - origin
            b.setLinearVel(tuple(lin + np.cross(ang, r)))
            b.setAngularVel(tuple(ang))

    def set_configuration(self, positions):
        """Place the links for the given joint positions {name: value} (others keep theirs)
        with the model pose unchanged, and zero all velocities (set_model_configuration)."""
        self.wake()
        for name in positions:
            if name not in self.joints:
                raise ModelError("model '%s' has no joint '%s'" % (self.name, name))
        q = {n: j.position() for n, j in self.joints.items()}
        q.update({k: float(v) for k, v in positions.items()})
        fixed = any(j.parent == 'world' for j in self.desc.joints)
        model_pose = self.initial_pose if fixed else self.pose()
        rel = _forward_kinematics(self.desc, q)
        for name, link in self.links.items():
            if link.body is None or name not in rel:
                continue
            bp = model_pose * rel[name] * link.desc.pose * link.com
            link.body.setPosition(tuple(bp.p))
            link.body.setQuaternion(_ode_q(bp.q))
        self.set_twist((0, 0, 0), (0, 0, 0))
        for b in self.bodies():
            b.enable()


def _welded_to_world(desc):
    """Links held by the world through fixed joints only (a URDF 'world' link, an SDF joint to
    'world'): they get no body, so they neither move nor fight contacts with the static world."""
    welded = {'world'}
    grew = True
    while grew:
        grew = False
        for j in desc.joints:
            if j.type == 'fixed' and j.parent in welded and j.child not in welded:
                welded.add(j.child)
                grew = True
    welded.discard('world')
    return welded


def _forward_kinematics(desc, q):
    """Rigid motion of each link relative to the zero configuration, in the model frame:
    {link: Pose} such that link pose (model frame) = motion * link.pose. Roots (links no joint
    leads to) and the world do not move."""
    children = {}
    for j in desc.joints:
        children.setdefault(j.parent, []).append(j)
    has_parent = {j.child for j in desc.joints}
    motion = {'world': Pose()}
    motion.update({l.name: Pose() for l in desc.links if l.name not in has_parent})
    stack = list(motion)
    while stack:
        parent = stack.pop()
        for j in children.get(parent, []):
            v = q.get(j.name, 0.0)
            if j.type in ('revolute', 'continuous'):
                rot = Pose((0, 0, 0), quat_from_axis_angle(j.axis, v))
                local = Pose(j.anchor) * rot * Pose(-np.asarray(j.anchor))
            elif j.type == 'prismatic':
                local = Pose(np.asarray(j.axis) * v)
            else:
                local = Pose()
            motion[j.child] = motion[parent] * local
            stack.append(j.child)
    return motion


class PhysicsWorld:
    """ODE world + spaces + contacts, built from ode_sim.description.model descriptions."""

    def __init__(self, physics, gravity=(0.0, 0.0, -9.8)):
        self.physics = physics
        self.dt = physics.max_step_size
        self.world = ode.World()
        self.world.setGravity(tuple(gravity))
        self.world.setERP(physics.erp)
        self.world.setCFM(physics.cfm)
        self.world.setQuickStepNumIterations(int(physics.iters))
        self.world.setContactMaxCorrectingVel(physics.contact_max_correcting_vel)
        self.world.setContactSurfaceLayer(physics.contact_surface_layer)
        self.static_space = ode.HashSpace()
        self.contact_group = ode.JointGroup()
        _keep_alive(self.world, self.static_space, self.contact_group)
        # Resting bodies of models that allow it fall asleep (SDF <allow_auto_disable>, default
        # true, as Gazebo's ODE links) and cost nothing until something touches them.
        self.world.setAutoDisableLinearThreshold(0.01)
        self.world.setAutoDisableAngularThreshold(0.01)
        self.world.setAutoDisableSteps(10)
        self.world.setAutoDisableTime(0)
        self.models = {}
        self.time = 0.0
        self.steps = 0
        # time = _t0 + (steps - _steps0) * dt: exact multiples of the step, and it accumulates
        # (never jumps) when set_properties() changes the step
        self._t0, self._steps0 = 0.0, 0
        self.max_contacts = max(1, int(physics.max_contacts))
        self._surf = {}                 # geom -> (mu1, mu2, kp, kd, fdir1, bounce, model, body)
        self._dyn_spaces = []           # spaces of dynamic models
        self._space_bodies = {}         # model space -> its bodies (sleep test)
        # Model spaces are top-level spaces that never change parent (moving spaces between
        # parents left ODE with stale bounding boxes); sleeping ones just change list.
        self._awake = []                # spaces of models with a body awake
        self._dormant = []              # spaces of models whose bodies all sleep
        self._wake = []                 # dormant spaces touched this step
        self._contacts = 0              # contact joints created (counter)
        self._self_collide = []         # spaces whose links collide with each other
        self._joints = []
        self._active = []               # joints with per-step work
        self._tracked = []
        self._version = 0               # bumps when shapes change (ray caster / renderer refresh)
        self.use_step = physics.solver_type == 'world'

    # ----------------------------------------------------------------- building
    def add_model(self, desc):
        if desc.name in self.models:
            raise ModelError("a model named '%s' already exists" % desc.name)
        if not desc.links:
            raise ModelError("%s: model '%s' has no links" % (desc.source or 'model', desc.name))
        _boxes_for_meshes(desc)
        m = SimModel(self, desc)
        static = desc.static
        # bodies take the world's auto-disable flag when created (PyODE has no per-body setter)
        self.world.setAutoDisableFlag(bool(self.auto_disable(desc)))
        space = self.static_space if static else ode.HashSpace()
        if not static:
            _keep_alive(space)
        m.space = space
        world_of = desc.pose
        welded = _welded_to_world(desc)
        for ld in desc.links:
            link_world = world_of * ld.pose
            if static or ld.name in welded:
                link = SimLink(m, ld, None, Pose(), static_pose=link_world)
            else:
                link = self._make_body(m, ld, link_world)
            m.links[ld.name] = link
            for c in ld.collisions:
                geom = self._make_geom(c, space, link, link_world)
                if geom is not None:
                    link.geoms.append(geom)
        m.canonical = m.links.get(desc.canonical_link) or m.links[desc.links[0].name]
        for jd in desc.joints:
            self._make_joint(m, jd)
        if not static:
            self._dyn_spaces.append(space)
            self._awake.append(space)
            self._space_bodies[space] = m.bodies()
            if any(l.self_collide for l in desc.links):
                self._self_collide.append(space)
        self.models[desc.name] = m
        self._version += 1
        return m

    def _make_body(self, m, ld, link_world):
        inertial = ld.inertial
        if inertial is None or inertial.mass <= 0:
            raise ModelError("%s: link '%s' of model '%s' has no positive mass"
                             % (m.desc.source or 'model', ld.name, m.name))
        body = ode.Body(self.world)
        mass = ode.Mass()
        r = quat_to_matrix(inertial.pose.q)
        tensor = r @ inertial.tensor() @ r.T          # inertia about the COM, link axes
        mass.setParameters(inertial.mass, 0, 0, 0, tensor[0, 0], tensor[1, 1], tensor[2, 2],
                           tensor[0, 1], tensor[0, 2], tensor[1, 2])
        body.setMass(mass)
        com = Pose(inertial.pose.p)
        bp = link_world * com
        body.setPosition(tuple(bp.p))
        body.setQuaternion(_ode_q(bp.q))
        if not ld.gravity:
            body.setGravityMode(False)
        if ld.kinematic:
            body.setKinematic()
        return SimLink(m, ld, body, com)

    def _make_geom(self, c, space, link, link_world):
        g = c.geometry
        k = g.kind
        if k == 'plane':
            if link.body is not None:
                raise ModelError("%s: collision '%s' of link '%s': a plane can only be static"
                                 % (link.model.desc.source or 'model', c.name, link.name))
            pw = link_world * c.pose
            n = pw.rotate(np.asarray(g.normal, dtype=float))
            n = n / np.linalg.norm(n)
            geom = ode.GeomPlane(space, tuple(n), float(np.dot(n, pw.p)))
        else:
            if k == 'box':
                geom = ode.GeomBox(space, tuple(float(v) for v in g.size))
            elif k == 'sphere':
                geom = ode.GeomSphere(space, float(g.radius))
            elif k == 'cylinder':
                geom = ode.GeomCylinder(space, float(g.radius), float(g.length))
            elif k == 'mesh':
                raise AssertionError('mesh collisions are replaced by boxes in add_model')
            else:
                raise ModelError("%s: collision '%s' of link '%s': unknown geometry '%s'"
                                 % (link.model.desc.source or 'model', c.name, link.name, k))
            if link.body is not None:
                geom.setBody(link.body)
                off = link.com.inverse() * c.pose
                geom.setOffsetPosition(tuple(off.p))
                geom.setOffsetQuaternion(_ode_q(off.q))
            else:
                pw = link_world * c.pose
                geom.setPosition(tuple(pw.p))
                geom.setQuaternion(_ode_q(pw.q))
        s = c.surface
        fdir = tuple(s.fdir1) if s.fdir1 is not None and any(s.fdir1) else None
        self._surf[geom] = (s.mu1, s.mu2, s.kp, s.kd, fdir, s.bounce, s.bounce_threshold,
                            link.body)
        geom.shape = c
        geom.link = link
        return geom

    def _make_joint(self, m, jd):
        parent = None if jd.parent == 'world' else m.links.get(jd.parent)
        child = m.links.get(jd.child)
        src = m.desc.source or 'model'
        if child is None or (parent is None and jd.parent != 'world'):
            raise ModelError("%s: joint '%s' connects unknown links '%s' -> '%s'"
                             % (src, jd.name, jd.parent, jd.child))
        if m.static:
            return None
        if jd.type == 'fixed' and child.body is None:
            return None                 # welded to the world: the link itself is static
        pb = parent.body if parent is not None and parent.body is not None else ENV
        cb = child.body
        if cb is None:
            raise ModelError("%s: joint '%s': child link '%s' has no body" % (src, jd.name, jd.child))
        origin = m.desc.pose
        anchor = origin.apply(jd.anchor)
        axis = origin.rotate(jd.axis)
        t = jd.type
        if t in ('revolute', 'continuous'):
            j = ode.HingeJoint(self.world)
            j.attach(cb, pb)
            j.setAnchor(tuple(anchor))
            j.setAxis(tuple(axis))
            if t == 'revolute' and jd.lower is not None and jd.upper is not None \
                    and jd.upper >= jd.lower:
                j.setParam(P_LO_STOP, jd.lower)
                j.setParam(P_HI_STOP, jd.upper)
        elif t == 'prismatic':
            j = ode.SliderJoint(self.world)
            j.attach(cb, pb)
            j.setAxis(tuple(axis))
            if jd.lower is not None and jd.upper is not None and jd.upper >= jd.lower:
                j.setParam(P_LO_STOP, jd.lower)
                j.setParam(P_HI_STOP, jd.upper)
        elif t == 'fixed':
            j = ode.FixedJoint(self.world)
            j.attach(cb, pb)
            j.setFixed()
        elif t == 'ball':
            j = ode.BallJoint(self.world)
            j.attach(cb, pb)
            j.setAnchor(tuple(anchor))
        else:
            raise ModelError("%s: joint '%s': type '%s' is not supported" % (src, jd.name, t))
        if t in ('revolute', 'continuous', 'prismatic'):
            j.setFeedback(True)
        sj = SimJoint(m, jd, j, parent, child)
        m.joints[jd.name] = sj
        self._joints.append(sj)
        if sj.hinge or sj.slider:
            sj._idle_motor()
        self._refresh_active()
        return sj

    def _refresh_active(self):
        self._active = [j for j in self._joints if j.active]

    def remove_model(self, name):
        m = self.models.pop(name, None)
        if m is None:
            return False
        for sj in m.joints.values():
            self._joints.remove(sj)
        self._refresh_active()
        for link in m.links.values():
            for g in link.geoms:
                self._surf.pop(g, None)
                if g.getSpace() is not None:
                    g.getSpace().remove(g)
                g.link = None
                g.shape = None
            if link in self._tracked:
                self._tracked.remove(link)
            if link.body is not None:
                link.body.disable()
        if m.space in self._dyn_spaces:
            self._dyn_spaces.remove(m.space)
            self._space_bodies.pop(m.space, None)
            for lst in (self._awake, self._dormant):
                if m.space in lst:
                    lst.remove(m.space)
        if m.space in self._self_collide:
            self._self_collide.remove(m.space)
        # ODE frees bodies/joints when the Python objects go away; detach joints first
        for sj in m.joints.values():
            sj.joint.attach(None, None)
        m.links.clear()
        m.joints.clear()
        self._version += 1
        return True

    # ----------------------------------------------------------------- stepping
    def track_acceleration(self, link):
        """Keep link.accel (world linear acceleration of the body, m/s^2) up to date."""
        if link.body is not None and link not in self._tracked:
            link.prev_vel = np.array(link.body.getLinearVel())
            self._tracked.append(link)

    @staticmethod
    def auto_disable(desc):
        """Robots (spawned from URDF, driven by plugins) stay awake; other models may sleep."""
        return not desc.urdf and desc.allow_auto_disable

    def _near(self, _arg, g1, g2):
        if g1.isSpace() or g2.isSpace():
            ode.collide2(g1, g2, None, self._near)
            return
        s1 = self._surf.get(g1)
        s2 = self._surf.get(g2)
        if s1 is None or s2 is None:
            return
        b1, b2 = s1[7], s2[7]
        if b1 is b2:
            return                      # one body, or two bodiless (static, welded) geoms
        if b1 is not None and b2 is not None and ode.areConnected(b1, b2):
            return
        contacts = ode.collide(g1, g2)
        if not contacts:
            return
        dt = self.dt
        kp = 1.0 / (1.0 / s1[2] + 1.0 / s2[2])
        kd = s1[3] + s2[3]
        denom = dt * kp + kd
        erp = dt * kp / denom
        cfm = 1.0 / denom
        mu1 = min(s1[0], s2[0])
        mu2 = min(s1[1], s2[1])
        fdir = s1[4] or s2[4]
        bounce = max(s1[5], s2[5])
        mode = ode.ContactSoftERP | ode.ContactSoftCFM | ode.ContactApprox1 | ode.ContactMu2
        if fdir is not None:
            mode |= ode.ContactFDir1
        if bounce > 0:
            mode |= ode.ContactBounce
        world = self.world
        group = self.contact_group
        for c in contacts[:self.max_contacts]:
            c.setMode(mode)
            c.setMu(mu1 if mu1 < 1e30 else ode.Infinity)
            c.setMu2(mu2 if mu2 < 1e30 else ode.Infinity)
            c.setSoftERP(erp)
            c.setSoftCFM(cfm)
            if fdir is not None:
                body = b1 if s1[4] else b2
                d = body.vectorToWorld(fdir) if body is not None else fdir
                c.setFDir1(d)
            if bounce > 0:
                c.setBounce(bounce)
                c.setBounceVel(min(s1[6], s2[6]))
            ode.ContactJoint(world, group, c).attach(b1, b2)
        self._contacts += 1

    def _sort_sleepers(self):
        """Models whose bodies all sleep stop colliding with the static world (and back)."""
        for sp in list(self._awake):
            if not any(b.isEnabled() for b in self._space_bodies[sp]):
                self._awake.remove(sp)
                self._dormant.append(sp)
        for sp in list(self._dormant):
            if any(b.isEnabled() for b in self._space_bodies[sp]):
                self._rouse(sp)

    def _rouse(self, sp):
        if sp in self._dormant:
            self._dormant.remove(sp)
            self._awake.append(sp)
            for b in self._space_bodies[sp]:
                b.enable()

    def step(self, n=1):
        dt = self.dt
        static = self.static_space
        near = self._near
        for _ in range(n):
            for sj in self._active:
                sj._pre_step(dt)
            awake = self._awake
            for i, sp in enumerate(awake):
                ode.collide2(sp, static, None, near)        # model vs the static world
                for other in awake[i + 1:]:
                    ode.collide2(sp, other, None, near)     # models vs each other
                for other in self._dormant:
                    before = self._contacts
                    ode.collide2(sp, other, None, near)     # a touch wakes the sleeper
                    if self._contacts != before:
                        self._wake.append(other)
            if self._wake:
                for sp in self._wake:
                    if sp in self._dormant:
                        self._rouse(sp)
                        ode.collide2(sp, static, None, near)
                self._wake = []
            for sp in self._self_collide:
                sp.collide(None, near)
            if self.use_step:
                self.world.step(dt)
            else:
                self.world.quickStep(dt)
            self.contact_group.empty()
            for link in self._tracked:
                v = np.array(link.body.getLinearVel())
                link.accel = (v - link.prev_vel) / dt
                link.prev_vel = v
            self.steps += 1
            self.time = self._t0 + (self.steps - self._steps0) * dt
            if self.steps % 100 == 0:
                self._sort_sleepers()

    # ----------------------------------------------------------------- state
    def reset_world(self):
        """Every model back to the pose it was spawned at, joints at zero, no motion."""
        for m in self.models.values():
            if m.static:
                continue
            rel = _forward_kinematics(m.desc, {})
            for name, link in m.links.items():
                if link.body is None:
                    continue
                bp = m.initial_pose * rel.get(name, Pose()) * link.desc.pose * link.com
                link.body.setPosition(tuple(bp.p))
                link.body.setQuaternion(_ode_q(bp.q))
                link.body.setLinearVel((0, 0, 0))
                link.body.setAngularVel((0, 0, 0))
                link.body.enable()
            for sj in m.joints.values():
                sj.release()
            m.wake()
        for link in self._tracked:
            link.prev_vel = np.zeros(3)
            link.accel = np.zeros(3)

    def reset_time(self):
        self.steps = 0
        self.time = 0.0
        self._t0, self._steps0 = 0.0, 0

    @property
    def gravity(self):
        return tuple(self.world.getGravity())

    def set_properties(self, time_step=None, gravity=None, iters=None, cfm=None, erp=None,
                       contact_surface_layer=None, contact_max_correcting_vel=None,
                       max_contacts=None):
        """Everything /gazebo/set_physics_properties can change; None leaves a value alone.
        Simulated time keeps accumulating across a change of the step."""
        if time_step is not None:
            if not time_step > 0:
                raise ValueError('time_step must be positive, got %r' % (time_step,))
            self._t0, self._steps0 = self.time, self.steps
            self.dt = float(time_step)
        if gravity is not None:
            self.world.setGravity(tuple(float(v) for v in gravity))
            for m in self.models.values():
                m.wake()
        if iters is not None:
            self.world.setQuickStepNumIterations(int(iters))
        if cfm is not None:
            self.world.setCFM(float(cfm))
        if erp is not None:
            self.world.setERP(float(erp))
        if contact_surface_layer is not None:
            self.world.setContactSurfaceLayer(float(contact_surface_layer))
        if contact_max_correcting_vel is not None:
            self.world.setContactMaxCorrectingVel(float(contact_max_correcting_vel))
        if max_contacts is not None:
            self.max_contacts = max(1, int(max_contacts))

    # ----------------------------------------------------------------- shapes
    @property
    def version(self):
        return self._version

    def collision_shapes(self):
        """ShapeInstance per collision geometry of every model (for the ray caster)."""
        out = []
        for m in self.models.values():
            for link in m.links.values():
                for c in link.desc.collisions:
                    out.append(self._instance(m, link, c.name, c.geometry, c.pose, None, c))
        return out

    def visual_shapes(self):
        """ShapeInstance per visual of every model (for the renderer and the scene markers)."""
        out = []
        for m in self.models.values():
            for link in m.links.values():
                for v in link.desc.visuals:
                    out.append(self._instance(m, link, v.name, v.geometry, v.pose, v.color, v))
        return out

    @staticmethod
    def _instance(m, link, name, geometry, local, color, desc):
        inst = ShapeInstance(key='%s::%s::%s' % (m.name, link.name, name), model=m.name,
                             link=link.name, geometry=geometry, local=local,
                             color=tuple(color) if color is not None else (0.7, 0.7, 0.7, 1.0),
                             link_pose=None if link.body is None else link.pose,
                             static_pose=link.pose() if link.body is None else Pose())
        inst.laser_retro = getattr(desc, 'laser_retro', 0.0)
        return inst


def _boxes_for_meshes(desc):
    """Debian's PyODE is built without ODE's triangle-mesh collider (TriMeshData raises
    NotImplementedError), so a mesh collision becomes the mesh's bounding box, with a warning.
    The description itself is changed, so the ray caster sees exactly what the physics does."""
    for link in desc.links:
        for c in link.collisions:
            g = c.geometry
            if g.kind != 'mesh':
                continue
            if g.vertices is None or len(g.vertices) == 0:
                raise ModelError("%s: collision '%s' of link '%s': mesh '%s' has no triangles"
                                 % (desc.source or 'model', c.name, link.name,
                                    g.uri or g.filename))
            lo = g.vertices.min(axis=0)
            hi = g.vertices.max(axis=0)
            size = tuple(float(max(v, 1e-4)) for v in hi - lo)
            c.pose = c.pose * Pose((lo + hi) / 2)
            c.geometry = Geometry('box', size=size)
            desc.warnings.append(
                "%s: collision '%s' of link '%s': mesh '%s' simulated as its bounding box "
                "%.3f x %.3f x %.3f m (Debian's PyODE has no triangle-mesh collider)"
                % (desc.source or desc.name, c.name, link.name, g.uri or g.filename, *size))


def physics_from_world(world_desc):
    """A PhysicsWorld with the world's physics settings and all its models."""
    pw = PhysicsWorld(world_desc.physics, world_desc.gravity)
    for m in world_desc.models:
        pw.add_model(m)
    return pw


def gravity_norm(pw):
    return math.sqrt(sum(v * v for v in pw.world.getGravity()))
