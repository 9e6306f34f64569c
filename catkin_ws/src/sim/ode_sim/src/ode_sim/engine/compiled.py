"""The compiled core (ode_sim.engine._core, C++ in engine/core/ on Debian's libode) driving the
step loop of a PhysicsWorld whose bodies, geoms and joints PyODE built.

PyODE gives the ids of geoms and spaces (`_id()`); those of worlds, bodies and joints are the
first field after the object header of its Cython structs. `check_layout()` verifies that on a
probe before any id is used, so a different PyODE fails with a clear error, not a crash.
Only engine/physics.py uses this module."""
import ctypes

import ode

from ode_sim.description.model import ModelError

try:
    from ode_sim.engine import _core
    _IMPORT_ERROR = None
except ImportError as e:            # not built: PhysicsWorld(core='compiled') fails clearly
    _core = None
    _IMPORT_ERROR = e

_HEAD = ctypes.sizeof(ctypes.c_ssize_t) + ctypes.sizeof(ctypes.c_void_p)   # PyObject_HEAD
_LAYOUT = []


def ptr(obj):
    """The ODE id (an integer) behind a PyODE world, space, body, geom or joint; 0 for None."""
    if obj is None or obj is ode.environment:
        return 0
    if hasattr(obj, '_id'):
        return int(obj._id())
    return ctypes.c_void_p.from_address(id(obj) + _HEAD).value or 0


def check_layout():
    """Raise ModelError unless the compiled core is importable and PyODE's ids read right."""
    if _core is None:
        raise ModelError('ode_sim: the compiled engine core ode_sim.engine._core is not built '
                         '(%s): build the workspace (scripts/build.sh)' % _IMPORT_ERROR)
    if _LAYOUT:
        if not _LAYOUT[0]:
            raise ModelError('ode_sim: this PyODE does not lay out its objects as the compiled '
                             'core expects (world/body/joint ids); use core="python"')
        return
    w = ode.World()
    space = ode.SimpleSpace()
    b = ode.Body(w)
    g = ode.GeomSphere(space, 0.1)
    g.setBody(b)
    j = ode.HingeJoint(w)
    j.attach(b, ode.environment)
    real_body = _core.geom_body(ptr(g))
    ok = real_body == ptr(b) and _core.body_world(real_body) == ptr(w) \
        and _core.body_joint(real_body, 0) == ptr(j)
    j.attach(None, None)
    space.remove(g)
    _LAYOUT.append(ok)
    check_layout()


_MESHES = {}    # id(vertices) -> (vertices, faces, _core.TriMesh): one ODE copy per loaded mesh


def trimesh_data(vertices, faces):
    """The _core.TriMesh of a loaded mesh (description/mesh.py caches its arrays, so every
    geom of one mesh file shares one ODE copy of the same triangles the ray caster uses)."""
    key = (id(vertices), id(faces))
    hit = _MESHES.get(key)
    if hit is None or hit[0] is not vertices or hit[1] is not faces:
        hit = (vertices, faces, _core.TriMesh(vertices, faces))
        _MESHES[key] = hit
    return hit[2]


class TriMeshGeom:
    """A libode trimesh geom made by the compiled core (Debian's PyODE has none), with the part
    of PyODE's geom interface PhysicsWorld uses. Destroyed with remove() or when collected."""

    def __init__(self, space, vertices, faces):
        check_layout()
        self.data = trimesh_data(vertices, faces)
        self.id = _core.TriMesh.create(self.data, ptr(space))
        self.space = space

    def _id(self):
        return self.id

    def setBody(self, body):
        _core.geom_set_body(self.id, ptr(body))

    def setOffsetPose(self, p, q_wxyz):
        _core.geom_set_offset(self.id, tuple(float(v) for v in p),
                              tuple(float(v) for v in q_wxyz))

    def setPose(self, p, q_wxyz):
        _core.geom_set_pose(self.id, tuple(float(v) for v in p), tuple(float(v) for v in q_wxyz))

    def getSpace(self):
        return self.space if self.id else None

    def getAABB(self):
        return _core.geom_aabb(self.id)

    def remove(self):
        if self.id:
            _core.geom_destroy(self.id)
            self.id = 0
            self.space = None

    def __del__(self):
        if _core is not None:
            self.remove()


class CompiledLoop:
    """PhysicsWorld's step loop in C++. PhysicsWorld tells it what changed (geoms, model
    spaces, joint commands, tracked links); step() runs n steps in one call, without the GIL."""

    def __init__(self, pw):
        check_layout()
        self.pw = pw
        self.core = _core.Stepper(ptr(pw.world), ptr(pw.static_space))
        self._geoms = {}            # ODE id -> geom (contact records name geoms by id)
        self._space_ids = {}        # see add_space
        self.joints_dirty = True
        self.tracked_dirty = True
        self.sync_step()

    def sync_step(self):
        pw = self.pw
        self.core.set_step(pw.dt, pw.use_step, pw.max_contacts)

    def add_geom(self, geom, surf):
        mu1, mu2, kp, kd, fdir, bounce, bounce_vel, body = surf
        self.core.add_geom(ptr(geom), ptr(body), mu1, mu2, kp, kd, fdir, bounce, bounce_vel)
        self._geoms[ptr(geom)] = geom

    def remove_geom(self, geom):
        self.core.remove_geom(ptr(geom))
        self._geoms.pop(ptr(geom), None)

    def set_watched(self, geoms):
        self.core.set_watched([ptr(g) for g in geoms])

    def take_contacts(self):
        """[(step, watched geom, other geom, 13 values)] recorded since the last call."""
        steps, ids, vals = self.core.take_contacts()
        geoms = self._geoms
        return [(int(s), geoms.get(int(a)), geoms.get(int(b)), v)
                for s, (a, b), v in zip(steps, ids, vals)]

    def add_space(self, space, bodies, self_collide):
        self.core.add_space(ptr(space), [ptr(b) for b in bodies], bool(self_collide))
        # the id of each model space, for rouse() (every commanded joint wakes its model
        # every step): id(space) -> (space, ODE id); the space is kept so its id is not reused
        self._space_ids[id(space)] = (space, ptr(space))

    def remove_space(self, space):
        self._space_ids.pop(id(space), None)
        self.core.remove_space(ptr(space))

    def rouse(self, space):
        e = self._space_ids.get(id(space))
        self.core.rouse(e[1] if e is not None and e[0] is space else ptr(space))

    def awake(self, space):
        return self.core.awake(ptr(space))

    def _push_joints(self):
        rows = []
        for j in self.pw._active:
            if not (j.hinge or j.slider):
                continue
            rows.append((ptr(j.joint), j.hinge, j.pos_cmd, float(j.effort_cmd),
                         float(j.desc.damping or 0.0), j.limit_velocity,
                         j.limit_effort if j.limit_effort is not None else 1e6))
        self._pushed = [j for j in self.pw._active if j.hinge or j.slider]
        self.core.set_joints(rows)
        self.joints_dirty = False

    def step(self, n):
        pw = self.pw
        if self.joints_dirty:
            self._push_joints()
        if self.tracked_dirty:
            self.core.set_tracked([ptr(link.body) for link in pw._tracked])
            self.tracked_dirty = False
        self.core.step(n, pw.steps)
        if self._pushed:
            for j, a in zip(self._pushed, self.core.applied()):
                j._applied = a
        if pw._tracked:
            for link, a in zip(pw._tracked, self.core.accels()):
                link.accel = a
        pw._contacts = self.core.contacts()

    def read_bodies(self, bodies):
        """(N, 13) array: position, quaternion (x y z w), linear and angular velocity."""
        return self.core.read_bodies([ptr(b) for b in bodies])
