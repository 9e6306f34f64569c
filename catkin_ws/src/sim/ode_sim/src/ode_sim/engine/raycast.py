"""Ray casting against the simulator's collision shapes, vectorised with numpy.

This module is RayCaster's interface and its NumPy implementation (core='python': the
reference); the default core='compiled' does the same casting in the engine's compiled core
(raycore.py, core/raycast.cpp), one call per scan, with the same results
(test/test_raycast_core.py).

`RayCaster(shapes).cast(origins, directions, max_range, exclude)` returns, per ray, the distance
to the first collision surface (np.inf when nothing is hit within max_range). It is what the
lidar (ray sensor) uses, and it hits the very geometry the physics collides with: the shapes
are the links' collisions (`ShapeInstance`), measured the way ODE's ray geom measures them
(test/test_raycast.py compares against pyODE's dGeomRay on the same shapes).

No Python loop per ray: every geometry kind is one batch of array operations over rays x shapes
of that kind. Static shapes are put in the world frame once (`set_shapes`); dynamic ones are
re-posed on every cast.

Geometry and semantics (those of ODE's dCollide with a dRayClass geom, which Gazebo's ray sensor
uses: ODEMultiRayShape calls dCollide after dGeomRaySetParams(ray, 0, 0), i.e. no
first-contact shortcut and no back-face culling, and dGeomRaySetClosestHit(ray, 1)):
  * box (size = full extents), sphere, cylinder (radius, length along the local Z axis, flat
    caps: ODE's dCylinder, which Gazebo creates for SDF/URDF cylinders; not a capsule).
  * plane: through the shape origin with the shape's normal, infinite. ODE's ray-plane test is
    two-sided: a ray hits the surface from above or from below (a ray starting below the
    plane, inside ODE's half-space, and pointing up hits at the surface; pointing down, none).
  * mesh (vertices already scaled, faces): Moller-Trumbore, both faces count (no back-face
    culling, as Gazebo sets it).
  * A ray that starts inside a solid reports where it leaves it: ODE's ray-box, ray-sphere and
    ray-cylinder colliders return the exit point when the start is inside; in a closed mesh
    the nearest triangle ahead is hit, the same thing. In general: the first surface crossing
    at distance >= min_range. Gazebo starts its rays at <range><min> (laser.py), which is what
    `min_range` gives without moving the origins. Gazebo does NOT exclude the sensor's own
    link; `exclude` lets a caller drop shapes (e.g. the sensor's own link).
  * Hits count when min_range <= distance < max_range. The nearest wins; on a tie the first
    in the caster's order: boxes, spheres, cylinders (rays from one origin: static ones
    first), then planes, then meshes (the lowest triangle of a hierarchy).

How it is fast enough (bench/raycast): when all rays share one origin (a lidar scan; also
`min_range` instead of moved origins), boxes, spheres, cylinders and the leaves of the mesh
hierarchy are culled by distance and by the azimuth interval their bounds subtend; the rays,
sorted by azimuth, are paired only with the bounds that can hold their hit (bisection), the
pairs get a slab test, and only the survivors the exact test. All static meshes share one
wide bounding-volume hierarchy (BVH) in the world frame; each dynamic mesh has its own in its
own frame. Rays with different origins are tested densely against the analytic shapes (rays x
shapes of a kind) and walk the BVH breadth-first, all at once. Arrays are kept per coordinate
(structure of arrays): numpy gathers and reductions over a trailing axis of 3 are several
times slower.
"""
import numpy as np

from ode_sim.description.model import ModelError
from ode_sim.engine.bvh import BVHForest, mesh_triangles
from ode_sim.engine.rayprims import (Fan, Posing, as_rays, k_box, k_cylinder, k_sphere,
                                     plane_hits, pose_arrays, record_hits, reduce_hits,
                                     shape_params, static_first, to_local)

KINDS = ('box', 'sphere', 'cylinder', 'plane', 'mesh')


class _Group:
    """Boxes, spheres, cylinders or planes of one kind, tested densely (rays x shapes)."""

    def __init__(self, kind, items):
        self.kind = kind
        self.index = np.array([i for i, _ in items], dtype=np.int64)
        self.shapes = [s for _, s in items]
        self.static = all(s.static for s in self.shapes)   # else all re-posed on every cast
        geoms = [s.geometry for s in self.shapes]
        if kind == 'box':
            self.half = np.array([np.asarray(g.size, dtype=float) / 2.0 for g in geoms])
        elif kind in ('sphere', 'cylinder'):
            self.radius = np.array([float(g.radius) for g in geoms])
            self.half_len = np.array([float(g.length) / 2.0 for g in geoms])
        else:
            n = np.array([np.asarray(g.normal, dtype=float) for g in geoms])
            norm = np.linalg.norm(n, axis=1)
            for s, nn in zip(self.shapes, norm):
                if not nn > 0:
                    raise ModelError('%s: plane normal %s has no direction'
                                     % (s.key, tuple(s.geometry.normal)))
            self.local_normal = n / norm[:, None]
        if self.static:
            self._posed = self._pose()
        else:
            self._posing = Posing(self.shapes)

    def _pose(self):
        rot, pos = pose_arrays(self.shapes) if self.static else self._posing()
        if self.kind == 'plane':
            n = np.einsum('kij,kj->ki', rot, self.local_normal)
            return n, np.einsum('ki,ki->k', n, pos)
        return rot, pos

    def hits(self, o, d, tmin, limit, excluded):
        a, b = self._posed if self.static else self._pose()
        if self.kind == 'plane':
            t, ok = plane_hits(o, d, a, b, tmin)
        elif self.kind == 'sphere':
            oc = [o[:, i] - b[:, i, None] for i in range(3)]
            t, ok = k_sphere(*oc, d[:, 0], d[:, 1], d[:, 2], self.radius[:, None], tmin)
        else:
            (ox, oy, oz), (dx, dy, dz) = to_local(o, d, a, b)
            if self.kind == 'box':
                h = self.half
                t, ok = k_box(ox, oy, oz, dx, dy, dz, h[:, 0, None], h[:, 1, None],
                              h[:, 2, None], tmin)
            else:
                t, ok = k_cylinder(ox, oy, oz, dx, dy, dz, self.radius[:, None],
                                   self.half_len[:, None], tmin)
        ok &= t <= limit
        if excluded is not None:
            ok &= ~excluded[self.index][:, None]
        return reduce_hits(t, ok)


class _Items:
    """Boxes, spheres and cylinders with world bounds, for rays from one origin: only the
    (ray, shape) pairs that survive Fan.candidates are tested. Static ones are posed once,
    dynamic ones on every cast."""

    CODES = {'box': 0, 'sphere': 1, 'cylinder': 2}

    def __init__(self, items):
        items = static_first(items)
        self.index = np.array([i for i, _ in items], dtype=np.int64)
        self.code = np.array([self.CODES[s.geometry.kind] for _, s in items], dtype=np.int64)
        self.dynamic = [s for _, s in items if not s.static]
        self.nstatic = len(items) - len(self.dynamic)
        p1 = shape_params(items)                    # box: half extents; others: radius, half len
        self.p1 = p1
        self.p1_soa = [np.ascontiguousarray(p1[:, i]) for i in range(3)]
        self._static = self._posed(*pose_arrays([s for _, s in items[:self.nstatic]]),
                                   slice(0, self.nstatic))
        self._posing = Posing(self.dynamic) if self.dynamic else None

    def _posed(self, rot, pos, part):
        """Rotation (K, 3, 3), position (K, 3) and world bounds (K, 3) x 2 of a part."""
        code, p1 = self.code[part], self.p1[part]
        ext = np.empty_like(pos)
        box = code == 0
        ext[box] = np.einsum('kij,kj->ki', np.abs(rot[box]), p1[box])
        ext[code == 1] = p1[code == 1, :1]
        cyl = code == 2
        axis = rot[cyl, :, 2]
        ext[cyl] = p1[cyl, 1:2] * np.abs(axis) + \
            p1[cyl, 0:1] * np.sqrt(np.maximum(1.0 - axis * axis, 0.0))
        pad = 1e-9 * (1.0 + np.abs(pos).max(initial=0.0) + ext.max(initial=0.0))
        return rot, pos, pos - ext - pad, pos + ext + pad

    def pose(self):
        if not self.dynamic:
            rot, pos, lo, hi = self._static
        else:
            dyn = self._posed(*self._posing(), slice(self.nstatic, None))
            rot, pos, lo, hi = (np.concatenate([a, b]) for a, b in zip(self._static, dyn))
        return rot, pos, [lo[:, i] for i in range(3)], [hi[:, i] for i in range(3)]

    def hits(self, fan, tmin, limit, excluded):
        """(t, shape index) per ray: nearest hit among the items (inf, -1 when none)."""
        best = np.full(fan.n, np.inf)
        who = np.full(fan.n, -1, dtype=np.int64)
        rot, pos, lo, hi = self.pose()
        if excluded is not None:
            use = np.flatnonzero(~excluded[self.index])
            lo = [a.take(use) for a in lo]
            hi = [a.take(use) for a in hi]
            k, r = fan.candidates(lo, hi, tmin, limit)
            k = use.take(k)
        else:
            k, r = fan.candidates(lo, hi, tmin, limit)
        if len(k) == 0:
            return best, who
        lc = np.einsum('kji,kj->ki', rot, np.asarray(fan.c) - pos)     # R^T (c - p)
        ox, oy, oz = (lc[:, i].take(k) for i in range(3))
        dw = [x.take(r) for x in fan.d]
        rk = rot.reshape(-1, 9)
        rr = [rk[:, j].take(k) for j in range(9)]   # rr[3 j + i] = R[j, i]
        dx = rr[0] * dw[0] + rr[3] * dw[1] + rr[6] * dw[2]     # d_local = R^T d
        dy = rr[1] * dw[0] + rr[4] * dw[1] + rr[7] * dw[2]
        dz = rr[2] * dw[0] + rr[5] * dw[1] + rr[8] * dw[2]
        p = [x.take(k) for x in self.p1_soa]
        code = self.code.take(k)
        t = np.full(len(k), np.inf)
        ok = np.zeros(len(k), dtype=bool)
        for c, kernel, nparam in ((0, k_box, 3), (1, k_sphere, 1), (2, k_cylinder, 2)):
            sel = np.flatnonzero(code == c)
            if len(sel) == 0:
                continue
            args = [a.take(sel) for a in (ox, oy, oz, dx, dy, dz)] + \
                [a.take(sel) for a in p[:nparam]]
            t[sel], ok[sel] = kernel(*args, tmin)
        ok &= t <= limit.take(r)
        return record_hits(best, who, r, t, k, ok, self.index)


class RayCaster:
    """First-hit ray casting against a list of ShapeInstance (collision shapes).

    core: 'compiled' (the default: the casting in the engine's compiled core, raycore.py and
    core/raycast.cpp) or 'python' (the NumPy implementation in this module: the reference the
    compiled one is tested against). PhysicsWorld(core=...) selects it for the simulator's
    sensors. Both give the same distances and shapes (test/test_raycast_core.py)."""

    def __init__(self, shapes, core='compiled'):
        if core not in ('compiled', 'python'):
            raise ValueError("RayCaster core must be 'compiled' or 'python', got %r" % (core,))
        self.core = core
        self.set_shapes(shapes)

    def set_shapes(self, shapes):
        self.shapes = list(shapes)
        self._pairs = [(s.model, s.link) for s in self.shapes]
        self._retro = None
        by_kind = {k: [] for k in KINDS}
        for i, s in enumerate(self.shapes):
            kind = s.geometry.kind
            if kind not in by_kind:
                raise ModelError('%s: geometry kind %r cannot be ray cast (known: %s)'
                                 % (s.key, kind, ', '.join(KINDS)))
            by_kind[kind].append((i, s))
        if self.core == 'compiled':
            from ode_sim.engine.raycore import CompiledRays
            self._compiled = CompiledRays(self.shapes, by_kind)
            return
        self._compiled = None
        # analytic shapes: dense groups, static and dynamic apart; the static solids also as
        # items culled per ray fan
        self._groups = [_Group(k, by_kind[k]) for k in ('box', 'sphere', 'cylinder', 'plane')
                        if by_kind[k]]
        self._planes = [g for g in self._groups if g.kind == 'plane']
        items = by_kind['box'] + by_kind['sphere'] + by_kind['cylinder']
        self._items = _Items(items) if items else None
        # meshes: all static ones in one world-frame hierarchy, each dynamic one in its own
        self._forest = BVHForest()
        self._static_root = None
        static = [(i, s) for i, s in by_kind['mesh'] if s.static]
        if static:
            tris = np.concatenate([s.world_pose().apply(mesh_triangles(s).reshape(-1, 3))
                                   .reshape(-1, 3, 3) for _, s in static])
            owner = np.concatenate([np.full(len(s.geometry.faces), i, dtype=np.int64)
                                    for i, s in static])
            self._static_root = self._forest.add(tris, owner)
        self._dyn_meshes = []
        for i, s in by_kind['mesh']:
            if not s.static:
                tris = mesh_triangles(s)
                root = self._forest.add(tris, np.full(len(tris), i, dtype=np.int64))
                self._dyn_meshes.append((i, s, root))
        self._forest.freeze()
        self._static_leaves = (self._forest.leaves_of(self._static_root)
                               if self._static_root is not None else None)

    def laser_retro(self):
        """(len(shapes),) the shapes' <laser_retro> (the lidar's intensity of a hit)."""
        if self._retro is None:
            self._retro = np.array([float(getattr(s, 'laser_retro', 0.0) or 0.0)
                                    for s in self.shapes])
        return self._retro

    def _excluded(self, exclude):
        if exclude is None:
            return None
        if callable(exclude):
            mask = np.fromiter((bool(exclude(s)) for s in self.shapes), dtype=bool,
                               count=len(self.shapes))
        else:
            ex = exclude if isinstance(exclude, (set, frozenset, dict)) else set(exclude)
            mask = np.fromiter((p in ex for p in self._pairs), dtype=bool,
                               count=len(self.shapes))
        return mask if mask.any() else None

    def cast(self, origins, directions, max_range, exclude=None, min_range=0.0):
        """Distance (N,) along each unit direction to the first hit, np.inf where nothing is
        hit within max_range. origins (N, 3) or (3,), directions (N, 3), world frame.
        exclude: callable(shape) -> bool, or a set of (model, link) pairs to ignore.
        min_range: surfaces nearer than this are ignored, as if each ray started there
        (Gazebo starts its rays at <range><min>); distances still count from the origin."""
        return self.cast_hits(origins, directions, max_range, exclude, min_range)[0]

    def cast_hits(self, origins, directions, max_range, exclude=None, min_range=0.0):
        """As cast(), plus (N,) the index in self.shapes of the shape hit (-1 for none)."""
        o, d, common = as_rays(origins, directions)
        n = len(d)
        tmin = max(float(min_range), 0.0)
        best = np.full(n, float(max_range))
        who = np.full(n, -1, dtype=np.int64)
        if n == 0 or not max_range >= tmin:
            return np.full(n, np.inf), who
        excluded = self._excluded(exclude)
        if self._compiled is not None:
            return self._compiled.cast_hits(o, d, common, tmin, max_range, excluded)
        fan = Fan(common, d) if common is not None else None

        def merge(t, k):
            better = (k >= 0) & (t < best)
            best[better] = t[better]
            who[better] = k[better]

        if fan is not None:
            if self._items is not None:
                merge(*self._items.hits(fan, tmin, best, excluded))
            groups = self._planes
        else:
            groups = self._groups
        for g in groups:
            t, k = g.hits(o, d, tmin, best, excluded)
            merge(t, np.where(k >= 0, g.index[np.maximum(k, 0)], -1))
        if not self._forest.empty:
            self._cast_meshes(o, d, fan, tmin, best, who, excluded)
        return np.where(who >= 0, best, np.inf), who

    def _cast_meshes(self, o, d, fan, tmin, best, who, excluded):
        n = len(d)
        tri_ok = None if excluded is None else ~excluded[self._forest.owner]
        frames_o, frames_d, ray_ids, roots = [], [], [], []
        base = np.arange(n)
        if self._static_root is not None:
            if fan is not None:
                t, k = self._forest.intersect_common(fan, tmin, best, self._static_leaves,
                                                     tri_ok)
                better = (k >= 0) & (t < best)
                best[better] = t[better]
                who[better] = k[better]
            else:
                frames_o.append(o)
                frames_d.append(d)
                ray_ids.append(base)
                roots.append(np.full(n, self._static_root, dtype=np.int64))
        for i, s, root in self._dyn_meshes:
            if excluded is not None and excluded[i]:
                continue
            pose = s.world_pose()
            rot = pose.rotation()
            ray_ids.append(base + len(frames_o) * n)
            frames_o.append((o - pose.p) @ rot)
            frames_d.append(d @ rot)
            roots.append(np.full(n, root, dtype=np.int64))
        if not ray_ids:
            return
        nf = len(frames_o)
        t, k = self._forest.intersect(np.concatenate(frames_o), np.concatenate(frames_d), tmin,
                                      np.tile(best, nf), np.concatenate(ray_ids),
                                      np.concatenate(roots), tri_ok)
        t = t.reshape(nf, n)
        k = k.reshape(nf, n)
        j = np.argmin(t, axis=0)
        tb = t[j, base]
        kb = k[j, base]
        better = (kb >= 0) & (tb < best)
        best[better] = tb[better]
        who[better] = kb[better]


def scan_directions(sensor_params):
    """Unit ray directions (N, 3) in the sensor frame, in Gazebo's order: for each vertical
    sample (outer loop, pitch from v_min_angle to v_max_angle) each horizontal sample (yaw
    from min_angle to max_angle, both ends included). See laser.py for the rules."""
    from ode_sim.engine.laser import scan_directions as directions
    return directions(sensor_params)
