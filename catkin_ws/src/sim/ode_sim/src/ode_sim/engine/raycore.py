"""The ray caster's shapes in the compiled core (ode_sim.engine._core.RayScene, C++ in
engine/core/raycast.cpp): RayCaster(shapes, core='compiled') hands them over once here and
casts every scan in one call without the GIL. The NumPy ray caster (core='python',
raycast.py) is the reference it is tested against (test/test_raycast_core.py).

What is handed over: boxes, spheres and cylinders (in raycast.py's item order, static ones
first) and planes with their world poses if static, else a slot: the shape's pose in its
link's frame (rayprims.Posing); the meshes' wide BVH forest exactly as bvh.py builds it (all
static meshes in one world-frame hierarchy, each dynamic mesh in its own). On every cast the
moving links' poses are read in one batch (Posing.links(): simulated links straight from
their ODE bodies) and passed with the rays; the core composes the shapes' poses."""
import numpy as np

from ode_sim.description.model import ModelError
from ode_sim.engine.bvh import BVHForest, mesh_triangles
from ode_sim.engine.rayprims import Posing, pose_arrays, shape_params, static_first

try:
    from ode_sim.engine import _core
    _IMPORT_ERROR = None
except ImportError as e:            # not built: RayCaster(core='compiled') fails clearly
    _core = None
    _IMPORT_ERROR = e

_CODES = {'box': 0, 'sphere': 1, 'cylinder': 2}


def available():
    return _core is not None and hasattr(_core, 'RayScene')


def _require():
    if not available():
        why = _IMPORT_ERROR or 'this build of ode_sim.engine._core has no RayScene'
        raise ModelError('ode_sim: the compiled ray caster ode_sim.engine._core.RayScene is not '
                         'built (%s): build the workspace (scripts/build.sh)' % why)


def _poses(shapes, slot_of):
    """(rot (K, 9), pos (K, 3), slot (K,)): static shapes posed, dynamic ones by slot."""
    rot = np.zeros((len(shapes), 3, 3))
    pos = np.zeros((len(shapes), 3))
    slot = np.full(len(shapes), -1, dtype=np.intc)
    static = [j for j, s in enumerate(shapes) if s.static]
    if static:
        r, p = pose_arrays([shapes[j] for j in static])
        rot[static] = r
        pos[static] = p
    for j, s in enumerate(shapes):
        if not s.static:
            slot[j] = slot_of[id(s)]
    return rot.reshape(-1, 9), pos, slot


class CompiledRays:
    """The shapes of one RayCaster in the compiled core (by_kind: kind -> [(index, shape)]
    in shape order)."""

    def __init__(self, shapes, by_kind):
        _require()
        self.scene = _core.RayScene(len(shapes))
        items = by_kind['box'] + by_kind['sphere'] + by_kind['cylinder']
        items = static_first(items)
        planes = by_kind['plane']
        meshes = by_kind['mesh']
        dynamic = [s for _, s in items + planes + meshes if not s.static]
        slot_of = {id(s): j for j, s in enumerate(dynamic)}
        self._posing = Posing(dynamic) if dynamic else None
        self._none = (np.zeros((0, 4)), np.zeros((0, 3)))

        if items:
            p = shape_params(items)
            rot, pos, slot = _poses([s for _, s in items], slot_of)
            self.scene.set_items(np.array([_CODES[s.geometry.kind] for _, s in items],
                                          dtype=np.intc),
                                 np.array([i for i, _ in items], dtype=np.int64), p, slot, rot,
                                 pos)
        if planes:
            n = np.array([np.asarray(s.geometry.normal, dtype=float) for _, s in planes])
            norm = np.linalg.norm(n, axis=1)
            for (_, s), nn in zip(planes, norm):
                if not nn > 0:
                    raise ModelError('%s: plane normal %s has no direction'
                                     % (s.key, tuple(s.geometry.normal)))
            rot, pos, slot = _poses([s for _, s in planes], slot_of)
            self.scene.set_planes(np.array([i for i, _ in planes], dtype=np.int64),
                                  n / norm[:, None], slot, rot, pos)
        if meshes:
            forest = BVHForest()
            static = [(i, s) for i, s in meshes if s.static]
            static_root = -1
            if static:
                tris = np.concatenate([s.world_pose().apply(mesh_triangles(s).reshape(-1, 3))
                                       .reshape(-1, 3, 3) for _, s in static])
                owner = np.concatenate([np.full(len(s.geometry.faces), i, dtype=np.int64)
                                        for i, s in static])
                static_root = forest.add(tris, owner)
            dyn = []
            for i, s in meshes:
                if not s.static:
                    tris = mesh_triangles(s)
                    dyn.append((i, forest.add(tris, np.full(len(tris), i, dtype=np.int64)),
                                slot_of[id(s)]))
            forest.freeze()
            self.scene.set_forest(np.stack(forest.lo, axis=1), np.stack(forest.hi, axis=1),
                                  forest.first, forest.count, forest.leaf.astype(np.uint8),
                                  np.stack(forest.v0, axis=1), np.stack(forest.e1, axis=1),
                                  np.stack(forest.e2, axis=1), forest.owner)
            self.scene.set_meshes(static_root, np.array([i for i, _, _ in dyn], dtype=np.int64),
                                  np.array([r for _, r, _ in dyn], dtype=np.int64),
                                  np.array([k for _, _, k in dyn], dtype=np.intc))

        if self._posing is not None:
            self.scene.set_slots(self._posing.idx, self._posing.local_rot,
                                 self._posing.local_pos, len(self._posing.calls))

    def cast_hits(self, o, d, common, tmin, max_range, excluded):
        """Rays as raycast.as_rays gives them; excluded: a bool mask per shape or None.
        Returns (t (N,), shape index (N,))."""
        q, p = self._posing.links() if self._posing is not None else self._none
        ex = None if excluded is None else excluded.view(np.uint8)
        origins = common if common is not None else o
        return self.scene.cast(origins, d, common is not None, float(tmin), float(max_range),
                               q, p, ex)
