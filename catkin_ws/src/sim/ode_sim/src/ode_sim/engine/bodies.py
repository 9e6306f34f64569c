"""Simulated links, joints and models: the engine's handles on the ODE bodies and joints that
PhysicsWorld (physics.py) builds. Conventions in physics.py's docstring."""
import ctypes

import numpy as np
import ode

from ode_sim.description.model import ModelError
from ode_sim.description.transforms import (Pose, qmul, qnormalize, qrotate,
                                            quat_from_axis_angle, quat_to_matrix)

ENV = ode.environment

# Joint parameter numbers of the ODE library actually linked (libode 0.16): PyODE 1.2 still
# exports the pre-0.13 numbering (ode.ParamFMax == 3, which is dParamLoVel in 0.16), so setting
# a motor's force through ode.ParamFMax silently does nothing. These are dParam* of 0.16.
P_LO_STOP, P_HI_STOP, P_VEL, P_LO_VEL, P_HI_VEL, P_FMAX = 0, 1, 2, 3, 4, 5

# ODE worlds, spaces and joint groups are never freed. PyODE's objects clear their references
# in arbitrary order when the garbage collector breaks a cycle (or the interpreter exits), so a
# world could be destroyed before its bodies (dBodyDestroy on freed memory: segfault). Bodies,
# joints and geoms are still freed; only these small containers stay, one set per PhysicsWorld.


def keep_alive(*objs):
    for obj in objs:
        ctypes.pythonapi.Py_IncRef(ctypes.py_object(obj))


def ode_q(q):
    """(x, y, z, w) -> ODE's (w, x, y, z)."""
    return (q[3], q[0], q[1], q[2])


def ros_q(q):
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
        self._ci_p, self._ci_q = self._com_inv.tuples()
        self._in_model_inv = desc.pose.inverse().tuples()    # the model frame in this link's
        self._static_pose = static_pose
        self.geoms = []
        self.prev_vel = None            # for acceleration tracking
        self.accel = np.zeros(3)

    def pose(self):
        """The link frame in the world."""
        if self.body is None:
            return self._static_pose
        p, q = self.pose_tuples()
        return Pose.unit(p, q)

    def pose_tuples(self, local_q=None):
        """pose() as float tuples (p, q), computed without numpy; with local_q, q is the
        orientation of the frame rotated by local_q in the link frame (pose().q * local_q)."""
        if self.body is None:
            p, q = self._static_pose.tuples()
            return p, (q if local_q is None else qnormalize(qmul(q, local_q)))
        b = self.body
        w, x, y, z = b.getQuaternion()
        bq = qnormalize((x, y, z, w))
        bx, by, bz = b.getPosition()
        ox, oy, oz = qrotate(bq, self._ci_p)
        q = qmul(bq, self._ci_q)
        if local_q is not None:
            q = qmul(q, local_q)
        return (bx + ox, by + oy, bz + oz), qnormalize(q)

    def angular_velocity(self):
        """The world angular velocity as a float tuple (zero for a static link)."""
        if self.body is None:
            return (0.0, 0.0, 0.0)
        return tuple(self.body.getAngularVel())

    def body_frame(self):
        """(ODE body, the link frame in the body's frame) for batched pose reads: pose() is
        the body's pose times this; None for a static link (rayprims.Posing uses it)."""
        return None if self.body is None else (self.body, self._com_inv)

    def frame_pose(self, name):
        """A frame lumped into this link (URDF fixed joint) or the link itself, in the world."""
        if name == self.name or name not in self.desc.lumped:
            return self.pose()
        return Pose.unit(*self.frame_tuples(name))

    def frame_tuples(self, name):
        """frame_pose(name) as float tuples (p, q)."""
        p, q = self.pose_tuples()
        if name == self.name or name not in self.desc.lumped:
            return p, q
        lp, lq = self.desc.lumped[name].tuples()
        ox, oy, oz = qrotate(q, lp)
        return (p[0] + ox, p[1] + oy, p[2] + oz), qnormalize(qmul(q, lq))

    def point_velocity(self, point):
        """velocity(point) as float tuples (linear, angular)."""
        if self.body is None:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        return tuple(self.body.getPointVel(tuple(point))), tuple(self.body.getAngularVel())

    def velocity(self, point=None):
        """(linear velocity of `point` (world; default the link origin), angular velocity),
        both in the world frame."""
        lin, ang = self.point_velocity(self.pose_tuples()[0] if point is None else point)
        return np.array(lin), np.array(ang)

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
        self.body.setQuaternion(ode_q(target.q))
        self.body.setLinearVel(tuple(float(v) for v in linear))
        self.body.setAngularVel(tuple(float(v) for v in angular))

    def set_inertial(self, mass, inertia, com, gravity):
        """set_link_properties: `mass`, `inertia` (ixx, iyy, izz, ixy, ixz, iyz about the
        centre of mass, in the inertial frame's axes), the centre of mass position `com` (link
        frame) and the gravity mode; the link frame stays where it is."""
        ine = self.desc.inertial
        if ine is not None:
            ine.mass = float(mass)
            ine.ixx, ine.iyy, ine.izz, ine.ixy, ine.ixz, ine.iyz = (float(v) for v in inertia)
            ine.pose = Pose(tuple(com), ine.pose.q)
        self.desc.gravity = bool(gravity)
        body = self.body
        if body is None or ine is None:
            return
        frame = self.pose()
        lin, ang = self.velocity()
        r = quat_to_matrix(ine.pose.q)
        tensor = r @ ine.tensor() @ r.T
        m = ode.Mass()
        m.setParameters(max(ine.mass, 1e-9), 0, 0, 0, tensor[0, 0], tensor[1, 1], tensor[2, 2],
                        tensor[0, 1], tensor[0, 2], tensor[1, 2])
        body.setMass(m)
        body.setGravityMode(bool(gravity))
        com = Pose(ine.pose.p)
        self.com = com
        self._com_inv = com.inverse()
        self._ci_p, self._ci_q = self._com_inv.tuples()
        bp = frame * com
        body.setPosition(tuple(float(v) for v in bp.p))
        body.setQuaternion(ode_q(bp.q))
        body.setLinearVel(tuple(float(v) for v in lin + np.cross(ang, bp.p - frame.p)))
        self.wake()


class SimJoint:
    """A joint between two links (or a link and the world)."""

    def __init__(self, model, desc, joint, parent, child):
        self.model = model
        self.name = desc.name
        self.desc = desc
        self.type = desc.type
        # plain attributes, not properties: read several times per joint and step
        self.hinge = self.type in ('revolute', 'continuous')
        self.slider = self.type == 'prismatic'
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
        was = self.active
        self.active = bool(self.pos_cmd is not None or self.effort_cmd or self.desc.damping)
        if was or self.active:          # the compiled loop's joint rows change
            self.world_ref._refresh_active()

    def set_ode_properties(self, damping=None, params=()):
        """set_joint_properties: the joint's viscous damping (None: unchanged) and ODE joint
        parameters as (dParam number of libode 0.16, value) pairs, on hinges and sliders only;
        a motor setting (vel, fmax: P_VEL, P_FMAX) wakes the child link."""
        if damping is not None:
            self.desc.damping = float(damping)
            self._update_active()
        if self.hinge or self.slider:
            params = list(params)
            for num, value in params:
                self.joint.setParam(num, float(value))
            if any(num in (P_VEL, P_FMAX) for num, _ in params):
                self.child.wake()

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
        cmd = (float(velocity), float(fmax))
        if cmd == self.vel_cmd and self.pos_cmd is None and not self.effort_cmd:
            # the motor already drives at this target (a drive plugin repeating its command
            # at its update rate): only the wake-up is left to do
            if self.hinge or self.slider:
                self.child.wake()
            return
        self.pos_cmd = None
        self.effort_cmd = 0.0
        self.vel_cmd = cmd
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

    def pre_step(self, dt):
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
        return Pose.unit(*self.pose_tuples())

    def pose_tuples(self):
        """pose() as float tuples (p, q), computed without numpy (/gazebo/model_states goes out
        every step)."""
        c = self.canonical
        if c is None:
            return self.initial_pose.tuples()
        (x, y, z), q = c.pose_tuples()
        ip, iq = c._in_model_inv
        ox, oy, oz = qrotate(q, ip)
        return (x + ox, y + oy, z + oz), qnormalize(qmul(q, iq))

    def twist(self):
        """(linear, angular) world velocity of the model frame origin."""
        lin, ang = self.twist_tuples()
        return np.array(lin), np.array(ang)

    def twist_tuples(self, origin=None):
        """twist() as float tuples; `origin`: the model frame's position if already known."""
        if self.canonical is None:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        return self.canonical.point_velocity(self.pose_tuples()[0] if origin is None else origin)

    def bodies(self):
        return [l.body for l in self.links.values() if l.body is not None]

    def wake(self):
        """Wake every body (after a teleport, a push, a reset)."""
        if not self.static:
            self.world._rouse(self.space)
            for b in self.bodies():
                b.enable()

    def set_pose(self, pose):
        """Move the whole model rigidly so that its pose becomes `pose` (a static one too, as
        Gazebo's Model::SetWorldPose: its geoms are re-placed in the static space)."""
        if self.static:
            self._move_static(pose * self.pose().inverse())
            return
        self.wake()
        delta = pose * self.pose().inverse()
        for link in self.links.values():
            b = link.body
            if b is None:
                continue
            bp = delta * Pose(b.getPosition(), ros_q(b.getQuaternion()))
            b.setPosition(tuple(bp.p))
            b.setQuaternion(ode_q(bp.q))
            b.enable()

    def _move_static(self, delta):
        """Re-place every link and geom of a static model by `delta` (a world-frame Pose);
        the world's version bumps so ray casters and renderers re-pose their static shapes,
        and every dynamic model wakes (a sleeping one stops colliding with the static world)."""
        for link in self.links.values():
            link._static_pose = delta * link._static_pose
            for geom in link.geoms:
                _place_static_geom(geom, link._static_pose * geom.shape.pose)
        self.world.static_moved()

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
        rel = forward_kinematics(self.desc, q)
        for name, link in self.links.items():
            if link.body is None or name not in rel:
                continue
            bp = model_pose * rel[name] * link.desc.pose * link.com
            link.body.setPosition(tuple(bp.p))
            link.body.setQuaternion(ode_q(bp.q))
        self.set_twist((0, 0, 0), (0, 0, 0))
        for b in self.bodies():
            b.enable()


def welded_to_world(desc):
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


def forward_kinematics(desc, q):
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


def _place_static_geom(geom, world):
    """A bodiless geom placed at `world` (its collision's pose in the world): a plane gets new
    parameters (normal, offset), the compiled core's trimesh its pose, any other ODE geom its
    position and orientation."""
    if isinstance(geom, ode.GeomPlane):
        n = world.rotate(np.asarray(geom.shape.geometry.normal, dtype=float))
        n = n / np.linalg.norm(n)
        geom.setParams(tuple(float(v) for v in n), float(np.dot(n, world.p)))
    elif isinstance(geom, ode.GeomObject):
        geom.setPosition(tuple(float(v) for v in world.p))
        geom.setQuaternion(ode_q(world.q))
    else:
        geom.setPose(world.p, ode_q(world.q))
