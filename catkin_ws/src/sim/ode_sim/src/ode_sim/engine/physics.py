"""The physics world: model descriptions (ode_sim.description.model) become ODE bodies, geoms
and joints.

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
import math

import numpy as np
import ode

from ode_sim.description.model import Geometry, ModelError
from ode_sim.description.transforms import Pose, quat_to_matrix
from ode_sim.engine.bodies import (ENV, P_HI_STOP, P_LO_STOP, SimJoint, SimLink, SimModel,
                                   forward_kinematics, keep_alive, ode_q, welded_to_world)
from ode_sim.engine.compiled import CompiledLoop, TriMeshGeom
from ode_sim.engine.contacts import ContactWatch
from ode_sim.engine.pyloop import PythonLoop
from ode_sim.engine.scene import ShapeInstance


class PhysicsWorld:
    """ODE world + spaces + contacts, built from ode_sim.description.model descriptions."""

    def __init__(self, physics, gravity=(0.0, 0.0, -9.8), core='compiled'):
        """core: 'compiled' (the step loop in C++, engine/core) or 'python' (the same loop on
        PyODE: the reference the compiled core is tested against). The sensors' ray casting
        (PluginContext.raycaster) follows it: RayCaster(core=pw.core)."""
        if core not in ('compiled', 'python'):
            raise ValueError("PhysicsWorld core must be 'compiled' or 'python', got %r" % (core,))
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
        keep_alive(self.world, self.static_space, self.contact_group)
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
        self.core = core
        self._loop = CompiledLoop(self) if core == 'compiled' else PythonLoop(self)
        #: contact sensors: contacts.watch(key, geoms), contacts.take(key) (engine/contacts.py)
        self.contacts = ContactWatch(self._loop, self.time_at_step)

    # ----------------------------------------------------------------- building
    def add_model(self, desc):
        if desc.name in self.models:
            raise ModelError("a model named '%s' already exists" % desc.name)
        if not desc.links:
            raise ModelError("%s: model '%s' has no links" % (desc.source or 'model', desc.name))
        if self.core == 'python':
            _boxes_for_meshes(desc)
        m = SimModel(self, desc)
        static = desc.static
        # bodies take the world's auto-disable flag when created (PyODE has no per-body setter)
        self.world.setAutoDisableFlag(bool(self.auto_disable(desc)))
        space = self.static_space if static else ode.HashSpace()
        if not static:
            keep_alive(space)
        m.space = space
        world_of = desc.pose
        welded = welded_to_world(desc)
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
            self._loop.add_space(space, self._space_bodies[space], space in self._self_collide)
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
        body.setQuaternion(ode_q(bp.q))
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
                if self.core != 'compiled':
                    raise AssertionError('mesh collisions are replaced by boxes in add_model')
                geom = TriMeshGeom(space, *_mesh_arrays(c, link))
            else:
                raise ModelError("%s: collision '%s' of link '%s': unknown geometry '%s'"
                                 % (link.model.desc.source or 'model', c.name, link.name, k))
            mesh = isinstance(geom, TriMeshGeom)
            if link.body is not None:
                geom.setBody(link.body)
                off = link.com.inverse() * c.pose
                if mesh:
                    geom.setOffsetPose(off.p, ode_q(off.q))
                else:
                    geom.setOffsetPosition(tuple(off.p))
                    geom.setOffsetQuaternion(ode_q(off.q))
            else:
                pw = link_world * c.pose
                if mesh:
                    geom.setPose(pw.p, ode_q(pw.q))
                else:
                    geom.setPosition(tuple(pw.p))
                    geom.setQuaternion(ode_q(pw.q))
        s = c.surface
        fdir = tuple(s.fdir1) if s.fdir1 is not None and any(s.fdir1) else None
        self._surf[geom] = (s.mu1, s.mu2, s.kp, s.kd, fdir, s.bounce, s.bounce_threshold,
                            link.body)
        self._loop.add_geom(geom, self._surf[geom])
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
            raise ModelError("%s: joint '%s': child link '%s' has no body"
                             % (src, jd.name, jd.child))
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
        self._loop.joints_dirty = True

    def remove_model(self, name):
        m = self.models.pop(name, None)
        if m is None:
            return False
        for sj in m.joints.values():
            self._joints.remove(sj)
        self._refresh_active()
        self.contacts.forget(g for link in m.links.values() for g in link.geoms)
        for link in m.links.values():
            for g in link.geoms:
                self._surf.pop(g, None)
                self._loop.remove_geom(g)
                if isinstance(g, TriMeshGeom):
                    g.remove()
                elif g.getSpace() is not None:
                    g.getSpace().remove(g)
                g.link = None
                g.shape = None
            if link in self._tracked:
                self._tracked.remove(link)
                self._loop.tracked_dirty = True
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
        if not m.static:
            self._loop.remove_space(m.space)
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
            self._loop.tracked_dirty = True

    @staticmethod
    def auto_disable(desc):
        """Robots (spawned from URDF, driven by plugins) stay awake; other models may sleep."""
        return not desc.urdf and desc.allow_auto_disable

    def static_moved(self):
        """A static model was moved (SimModel.set_pose): shapes changed for the ray casters and
        renderers, and sleeping models must collide with the static world again."""
        self._version += 1
        for m in self.models.values():
            if not m.static:
                m.wake()

    def _rouse(self, sp):
        self._loop.rouse(sp)

    def time_after(self, k):
        """The simulated time after k more steps of the current dt (as step() will count it)."""
        return self._t0 + (self.steps + k - self._steps0) * self.dt

    def time_at_step(self, k):
        """The simulated time after step number k (k <= steps, of the current dt)."""
        return self._t0 + (k - self._steps0) * self.dt

    def step(self, n=1):
        """n physics steps of dt (one call into the loop)."""
        self._loop.step(n)
        self.steps += n
        self.time = self._t0 + (self.steps - self._steps0) * self.dt

    # ----------------------------------------------------------------- state
    def reset_world(self):
        """Every model back to the pose it was spawned at, joints at zero, no motion."""
        for m in self.models.values():
            if m.static:
                continue
            rel = forward_kinematics(m.desc, {})
            for name, link in m.links.items():
                if link.body is None:
                    continue
                bp = m.initial_pose * rel.get(name, Pose()) * link.desc.pose * link.com
                link.body.setPosition(tuple(bp.p))
                link.body.setQuaternion(ode_q(bp.q))
                link.body.setLinearVel((0, 0, 0))
                link.body.setAngularVel((0, 0, 0))
                link.body.enable()
            for sj in m.joints.values():
                sj.release()
            m.wake()
        for link in self._tracked:
            link.prev_vel = np.zeros(3)
            link.accel = np.zeros(3)
        self._loop.tracked_dirty = True

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
            self._loop.sync_step()
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
            self._loop.sync_step()

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
        inst.material = getattr(desc, 'material', None)
        return inst


def _mesh_arrays(c, link):
    """(vertices, faces) of a mesh collision as the description loaded them (already scaled):
    the compiled core's trimesh and the ray caster's BVH are built from these same arrays."""
    return _checked_mesh(c.geometry, c.name, link.name, link.model.desc.source or 'model')


def _checked_mesh(g, collision, link, source):
    if g.vertices is None or len(g.vertices) == 0 or g.faces is None or len(g.faces) == 0:
        raise ModelError("%s: collision '%s' of link '%s': mesh '%s' has no triangles"
                         % (source, collision, link, g.uri or g.filename))
    return g.vertices, g.faces


def _boxes_for_meshes(desc):
    """core='python' only: Debian's PyODE is built without ODE's triangle-mesh collider
    (TriMeshData raises NotImplementedError), so there a mesh collision becomes the mesh's
    bounding box, with a warning. The description itself is changed, so the ray caster sees
    exactly what the physics does. The compiled core collides the real triangles."""
    for link in desc.links:
        for c in link.collisions:
            g = c.geometry
            if g.kind != 'mesh':
                continue
            _checked_mesh(g, c.name, link.name, desc.source or 'model')
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
