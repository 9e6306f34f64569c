"""Ray casting against the simulator's collision shapes, vectorised with numpy.

`RayCaster(shapes).cast(origins, directions, max_range, exclude)` returns, per ray, the distance
to the first collision surface (np.inf when nothing is hit within max_range). It is what the
lidar (ray sensor) uses, and it hits the very geometry the physics collides with: the shapes
are the links' collisions (`ShapeInstance`), measured the way ODE's ray geom measures them
(test/test_raycast.py compares against pyODE's dGeomRay on the same shapes).

No Python loop per ray: every geometry kind is one batch of array operations over
rays x shapes of that kind (all boxes stacked, all spheres, ...). Static shapes are put in the
world frame once (`set_shapes`); dynamic ones are re-posed on every cast.

Geometry and semantics (matching ODE's dCollide of a dRayClass geom, which Gazebo's ray sensor
uses: ODEMultiRayShape calls dCollide with dGeomRaySetParams(ray, 0, 0) i.e. no first-contact
shortcut and no back-face culling, and dGeomRaySetClosestHit(ray, 1)):
  * box (size = full extents): slab test in the box frame.
  * sphere.
  * cylinder: radius, length along the local Z axis, flat caps (ODE dCylinder, which is what
    Gazebo creates for SDF/URDF cylinders; not a capsule).
  * plane: the plane through the shape origin with the shape's normal, infinite. ODE's
    ray-plane test is two-sided: a ray hits the surface from above or from below (a ray that
    starts below the plane, inside ODE's half-space, and points up hits at the surface; one
    pointing down hits nothing).
  * mesh (vertices already scaled, faces): Moller-Trumbore on triangles, both faces count (no
    back-face culling, as Gazebo sets it), culled by a wide bounding-volume hierarchy built
    once per mesh; all static meshes share one hierarchy in the world frame.
  * A ray that starts inside a solid (box, sphere, cylinder) reports where it leaves it (ODE
    does so: its ray-box/sphere/cylinder colliders return the exit point when the start is
    inside). Inside a closed mesh the nearest triangle ahead is hit, which is the same thing.
    Gazebo does NOT exclude the sensor's own link; its rays start at <range><min> (see
    laser.py), so a sensor inside its own collision sees the inside of it unless range_min
    reaches past it. `exclude` lets a caller drop shapes (e.g. the sensor's own link).
  * Hits count when 0 <= distance <= max_range.
"""
import math

import numpy as np

from .model import ModelError

KINDS = ('box', 'sphere', 'cylinder', 'plane', 'mesh')

_EPS = 1e-12
_LEAF = 8        # triangles per BVH leaf (at most)
_BRANCH = 8      # children per inner BVH node (at most): 3 levels of binary median splits


def _as_rays(origins, directions):
    d = np.asarray(directions, dtype=float)
    if d.ndim == 1:
        d = d.reshape(1, 3)
    if d.ndim != 2 or d.shape[1] != 3:
        raise ValueError('directions must be (N, 3), got shape %s' % (d.shape,))
    o = np.asarray(origins, dtype=float)
    if o.ndim == 1:
        if o.shape != (3,):
            raise ValueError('origins must be (3,) or (N, 3), got shape %s' % (o.shape,))
        o = np.broadcast_to(o, d.shape)
    elif o.shape != d.shape:
        raise ValueError('origins %s and directions %s differ in shape' % (o.shape, d.shape))
    return np.ascontiguousarray(o), np.ascontiguousarray(d)


def _pose_arrays(shapes):
    """World rotation matrices (K, 3, 3) and positions (K, 3) of shapes."""
    k = len(shapes)
    rot = np.empty((k, 3, 3))
    pos = np.empty((k, 3))
    for i, s in enumerate(shapes):
        pose = s.world_pose()
        rot[i] = pose.rotation()
        pos[i] = pose.p
    return rot, pos


def _reduce_hits(t, ok):
    """t, ok: (K, N). Per ray: nearest valid t and the row it came from (-1 when none)."""
    t = np.where(ok, t, np.inf)
    k = np.argmin(t, axis=0)
    best = t[k, np.arange(t.shape[1])]
    k[~np.isfinite(best)] = -1
    return best, k


# ---------------------------------------------------------------------------------------------
# analytic primitives: each takes rays (N, 3), stacked shape parameters, a per-ray limit (N,),
# and returns (t (K, N), ok (K, N))

def _to_local(o, d, rot, pos):
    """Rays into K shape frames: (K, N, 3) origins and directions (local = R^T (x - p))."""
    lo = np.matmul(o[None, :, :] - pos[:, None, :], rot)
    ld = np.matmul(d[None, :, :], rot)
    return lo, ld


def _box_hits(o, d, rot, pos, half, limit):
    lo, ld = _to_local(o, d, rot, pos)
    with np.errstate(divide='ignore', invalid='ignore'):
        inv = 1.0 / ld
        t1 = (-half[:, None, :] - lo) * inv
        t2 = (half[:, None, :] - lo) * inv
    # fmin/fmax skip the NaN of a ray lying in a slab's boundary plane (0 * inf)
    tn = np.fmax.reduce(np.fmin(t1, t2), axis=2)
    tf = np.fmin.reduce(np.fmax(t1, t2), axis=2)
    t = np.where(tn >= 0.0, tn, tf)                 # start inside: the exit point (as ODE)
    ok = (tn <= tf) & (tf >= 0.0) & (t <= limit[None, :])
    return t, ok


def _sphere_hits(o, d, pos, radius, limit):
    oc = o[None, :, :] - pos[:, None, :]            # (K, N, 3)
    b = np.einsum('knj,nj->kn', oc, d)
    c = np.einsum('knj,knj->kn', oc, oc) - (radius * radius)[:, None]
    disc = b * b - c
    sq = np.sqrt(np.maximum(disc, 0.0))
    t = -b - sq
    t = np.where(t >= 0.0, t, -b + sq)              # start inside: the far root (as ODE)
    ok = (disc >= 0.0) & (t >= 0.0) & (t <= limit[None, :])
    return t, ok


def _cylinder_hits(o, d, rot, pos, radius, half_len, limit):
    lo, ld = _to_local(o, d, rot, pos)
    ox, oy, oz = lo[..., 0], lo[..., 1], lo[..., 2]
    dx, dy, dz = ld[..., 0], ld[..., 1], ld[..., 2]
    r2 = (radius * radius)[:, None]
    hl = half_len[:, None]
    tol_r = r2 * (1.0 + 1e-12) + 1e-15
    tol_z = hl * (1.0 + 1e-12) + 1e-15
    a = dx * dx + dy * dy
    b = ox * dx + oy * dy
    c = ox * ox + oy * oy - r2
    disc = b * b - a * c
    sq = np.sqrt(np.maximum(disc, 0.0))
    side_ok = (disc >= 0.0) & (a > _EPS)
    best = np.full(a.shape, np.inf)
    with np.errstate(divide='ignore', invalid='ignore'):
        for t in ((-b - sq) / a, (-b + sq) / a):
            z = oz + t * dz
            good = side_ok & (t >= 0.0) & (np.abs(z) <= tol_z)
            best = np.where(good & (t < best), t, best)
        for zc in (hl, -hl):
            t = (zc - oz) / dz
            x = ox + t * dx
            y = oy + t * dy
            good = (t >= 0.0) & (x * x + y * y <= tol_r)
            best = np.where(good & (t < best), t, best)
    ok = np.isfinite(best) & (best <= limit[None, :])
    return best, ok


def _plane_hits(o, d, normal, offset, limit):
    den = normal @ d.T                              # (K, N)
    num = offset[:, None] - normal @ o.T
    with np.errstate(divide='ignore', invalid='ignore'):
        t = num / den
    ok = (den != 0.0) & (t >= 0.0) & (t <= limit[None, :])
    return t, ok


# ---------------------------------------------------------------------------------------------
# triangle meshes: a wide BVH forest, traversed breadth-first for all rays at once

def _expand(ids, starts, counts):
    """For each i: ids[i] repeated counts[i] times, paired with starts[i] + 0..counts[i]-1."""
    total = int(counts.sum())
    if total == 0:
        return ids[:0], starts[:0]
    rep = np.repeat(ids, counts)
    offs = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    return rep, np.repeat(starts, counts) + offs


class _BVHForest:
    """Triangle sets, each with its own hierarchy (root), stored in shared flat arrays."""

    def __init__(self):
        self.lo = []
        self.hi = []
        self.first = []      # first child node (inner) / first triangle (leaf)
        self.count = []      # number of children (inner) / triangles (leaf)
        self.leaf = []
        self.tris = []       # (T, 3, 3) per set, reordered
        self.owner = []      # (T,) per set
        self.roots = []
        self._ntri = 0
        self._nnode = 0

    def add(self, tris, owner):
        """Build the hierarchy of tris (T, 3, 3) whose triangle i belongs to owner[i];
        returns the root node index."""
        n = len(tris)
        cent = tris.mean(axis=1)
        perm = np.arange(n)
        ranges = [(0, n)]
        first = [0]
        count = [0]
        leaf = [True]

        def split(s, e, depth):
            if depth == 0 or e - s <= _LEAF:
                return [(s, e)]
            idx = perm[s:e]
            c = cent[idx]
            axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
            perm[s:e] = idx[np.argsort(c[:, axis], kind='stable')]
            m = (s + e) // 2
            return split(s, m, depth - 1) + split(m, e, depth - 1)

        i = 0
        levels = int(round(math.log2(_BRANCH)))
        while i < len(ranges):
            s, e = ranges[i]
            if e - s > _LEAF:
                kids = split(s, e, levels)
                first[i] = len(ranges)
                count[i] = len(kids)
                leaf[i] = False
                for ks, ke in kids:
                    ranges.append((ks, ke))
                    first.append(0)
                    count.append(0)
                    leaf.append(True)
            i += 1
        tris = tris[perm]
        owner = owner[perm]
        m = len(ranges)
        lo = np.empty((m, 3))
        hi = np.empty((m, 3))
        for j in range(m - 1, -1, -1):
            if leaf[j]:
                s, e = ranges[j]
                pts = tris[s:e].reshape(-1, 3)
                lo[j] = pts.min(axis=0)
                hi[j] = pts.max(axis=0)
                first[j] = s + self._ntri
                count[j] = e - s
            else:
                f, c = first[j], count[j]
                lo[j] = lo[f:f + c].min(axis=0)
                hi[j] = hi[f:f + c].max(axis=0)
                first[j] = f + self._nnode
        pad = 1e-9 * (1.0 + np.abs(lo).max(initial=0.0) + np.abs(hi).max(initial=0.0))
        self.lo.append(lo - pad)
        self.hi.append(hi + pad)
        self.first.append(np.asarray(first, dtype=np.int64))
        self.count.append(np.asarray(count, dtype=np.int64))
        self.leaf.append(np.asarray(leaf, dtype=bool))
        self.tris.append(tris)
        self.owner.append(owner)
        root = self._nnode
        self.roots.append(root)
        self._nnode += m
        self._ntri += n
        return root

    def freeze(self):
        if self._nnode == 0:
            self.empty = True
            return self
        self.empty = False
        self.lo = np.concatenate(self.lo)
        self.hi = np.concatenate(self.hi)
        self.first = np.concatenate(self.first)
        self.count = np.concatenate(self.count)
        self.leaf = np.concatenate(self.leaf)
        tris = np.concatenate(self.tris)
        self.v0 = np.ascontiguousarray(tris[:, 0])
        self.e1 = np.ascontiguousarray(tris[:, 1] - tris[:, 0])
        self.e2 = np.ascontiguousarray(tris[:, 2] - tris[:, 0])
        self.owner = np.concatenate(self.owner)
        del self.tris
        return self

    def intersect(self, o, d, limit, ray_ids, roots, tri_ok=None):
        """Rays o, d (R, 3) with per-ray limit (R,); initial (ray, root) pairs given by
        ray_ids and roots (equal length). Returns per ray the nearest t (inf if none) and the
        owner of the triangle hit (-1)."""
        nray = len(o)
        best = np.full(nray, np.inf)
        who = np.full(nray, -1, dtype=np.int64)
        if self.empty or len(ray_ids) == 0:
            return best, who
        with np.errstate(divide='ignore', invalid='ignore'):
            inv = 1.0 / d
        pr, pn = ray_ids, roots
        leaf_r, leaf_n = [], []
        while len(pr):
            oo = o[pr]
            iv = inv[pr]
            with np.errstate(invalid='ignore'):
                t1 = (self.lo[pn] - oo) * iv
                t2 = (self.hi[pn] - oo) * iv
            tn = np.fmax.reduce(np.fmin(t1, t2), axis=1)
            tf = np.fmin.reduce(np.fmax(t1, t2), axis=1)
            keep = (tn <= tf) & (tf >= 0.0) & (tn <= limit[pr])
            pr, pn = pr[keep], pn[keep]
            is_leaf = self.leaf[pn]
            if is_leaf.any():
                leaf_r.append(pr[is_leaf])
                leaf_n.append(pn[is_leaf])
                inner = ~is_leaf
                pr, pn = pr[inner], pn[inner]
            pr, pn = _expand(pr, self.first[pn], self.count[pn])
        if not leaf_r:
            return best, who
        lr = np.concatenate(leaf_r)
        ln = np.concatenate(leaf_n)
        r, tri = _expand(lr, self.first[ln], self.count[ln])
        if tri_ok is not None:
            keep = tri_ok[tri]
            r, tri = r[keep], tri[keep]
        t, ok = self._moller_trumbore(o[r], d[r], tri)
        ok &= t <= limit[r]
        r, t, tri = r[ok], t[ok], tri[ok]
        if len(r) == 0:
            return best, who
        order = np.lexsort((t, r))
        r, t, tri = r[order], t[order], tri[order]
        first = np.ones(len(r), dtype=bool)
        first[1:] = r[1:] != r[:-1]
        best[r[first]] = t[first]
        who[r[first]] = self.owner[tri[first]]
        return best, who

    def _moller_trumbore(self, o, d, tri):
        e1 = self.e1[tri]
        e2 = self.e2[tri]
        dx, dy, dz = d[:, 0], d[:, 1], d[:, 2]
        ax, ay, az = e1[:, 0], e1[:, 1], e1[:, 2]
        bx, by, bz = e2[:, 0], e2[:, 1], e2[:, 2]
        px = dy * bz - dz * by                      # p = d x e2
        py = dz * bx - dx * bz
        pz = dx * by - dy * bx
        det = ax * px + ay * py + az * pz
        tv = o - self.v0[tri]
        tx, ty, tz = tv[:, 0], tv[:, 1], tv[:, 2]
        qx = ty * az - tz * ay                      # q = tv x e1
        qy = tz * ax - tx * az
        qz = tx * ay - ty * ax
        with np.errstate(divide='ignore', invalid='ignore'):
            inv = 1.0 / det
            u = (tx * px + ty * py + tz * pz) * inv
            v = (dx * qx + dy * qy + dz * qz) * inv
            t = (bx * qx + by * qy + bz * qz) * inv
            tol = 1e-12
            ok = (np.abs(det) > 1e-300) & (u >= -tol) & (v >= -tol) & (u + v <= 1.0 + tol) \
                & (t >= 0.0)
        return t, ok


def _mesh_triangles(shape):
    g = shape.geometry
    if g.vertices is None or g.faces is None or len(g.faces) == 0:
        raise ModelError('%s: mesh %r has no triangles loaded (vertices/faces missing)'
                         % (shape.key, g.uri or g.filename))
    v = np.asarray(g.vertices, dtype=float)
    f = np.asarray(g.faces, dtype=np.int64)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise ModelError('%s: mesh %r needs (N, 3) vertices and (M, 3) faces, got %s and %s'
                         % (shape.key, g.uri or g.filename, v.shape, f.shape))
    if f.min() < 0 or f.max() >= len(v):
        raise ModelError('%s: mesh %r has face indices outside its %d vertices'
                         % (shape.key, g.uri or g.filename, len(v)))
    return v[f]                                     # (M, 3, 3) in the shape frame


# ---------------------------------------------------------------------------------------------

class _Group:
    """Shapes of one analytic kind: static ones in the world frame, dynamic ones re-posed."""

    def __init__(self, kind, items):
        self.kind = kind
        static = [(i, s) for i, s in items if s.static]
        dynamic = [(i, s) for i, s in items if not s.static]
        self.index = np.array([i for i, _ in static] + [i for i, _ in dynamic], dtype=np.int64)
        self.dynamic = [s for _, s in dynamic]
        shapes = [s for _, s in static] + self.dynamic
        self.size = len(shapes)
        geoms = [s.geometry for s in shapes]
        if kind == 'box':
            self.half = np.array([np.asarray(g.size, dtype=float) / 2.0 for g in geoms])
        elif kind == 'sphere':
            self.radius = np.array([float(g.radius) for g in geoms])
        elif kind == 'cylinder':
            self.radius = np.array([float(g.radius) for g in geoms])
            self.half_len = np.array([float(g.length) / 2.0 for g in geoms])
        elif kind == 'plane':
            n = np.array([np.asarray(g.normal, dtype=float) for g in geoms])
            self.local_normal = n / np.linalg.norm(n, axis=1)[:, None]
        self.rot, self.pos = _pose_arrays([s for _, s in static])
        self.nstatic = len(static)
        if kind == 'plane':
            self.static_normal, self.static_offset = self._plane_world(
                self.rot, self.pos, self.local_normal[:self.nstatic])

    @staticmethod
    def _plane_world(rot, pos, local_normal):
        n = np.einsum('kij,kj->ki', rot, local_normal)
        return n, np.einsum('ki,ki->k', n, pos)

    def poses(self):
        if not self.dynamic:
            return self.rot, self.pos
        rot, pos = _pose_arrays(self.dynamic)
        return np.concatenate([self.rot, rot]), np.concatenate([self.pos, pos])

    def hits(self, o, d, limit, excluded):
        if self.kind == 'plane':
            if self.dynamic:
                rot, pos = _pose_arrays(self.dynamic)
                n, off = self._plane_world(rot, pos, self.local_normal[self.nstatic:])
                n = np.concatenate([self.static_normal, n])
                off = np.concatenate([self.static_offset, off])
            else:
                n, off = self.static_normal, self.static_offset
            t, ok = _plane_hits(o, d, n, off, limit)
        elif self.kind == 'sphere':
            _, pos = self.poses() if self.dynamic else (None, self.pos)
            t, ok = _sphere_hits(o, d, pos, self.radius, limit)
        else:
            rot, pos = self.poses()
            if self.kind == 'box':
                t, ok = _box_hits(o, d, rot, pos, self.half, limit)
            else:
                t, ok = _cylinder_hits(o, d, rot, pos, self.radius, self.half_len, limit)
        if excluded is not None:
            ok &= ~excluded[self.index][:, None]
        return _reduce_hits(t, ok)


class RayCaster:
    """First-hit ray casting against a list of ShapeInstance (collision shapes)."""

    def __init__(self, shapes):
        self.set_shapes(shapes)

    def set_shapes(self, shapes):
        self.shapes = list(shapes)
        self._pairs = [(s.model, s.link) for s in self.shapes]
        by_kind = {k: [] for k in KINDS}
        for i, s in enumerate(self.shapes):
            kind = s.geometry.kind
            if kind not in by_kind:
                raise ModelError('%s: geometry kind %r cannot be ray cast (known: %s)'
                                 % (s.key, kind, ', '.join(KINDS)))
            by_kind[kind].append((i, s))
        self._groups = [_Group(k, by_kind[k]) for k in ('box', 'sphere', 'cylinder', 'plane')
                        if by_kind[k]]
        # meshes: all static ones in one world-frame hierarchy, each dynamic one in its own frame
        self._forest = _BVHForest()
        static = [(i, s) for i, s in by_kind['mesh'] if s.static]
        self._static_root = None
        if static:
            tris, owner = [], []
            for i, s in static:
                tris.append(s.world_pose().apply(_mesh_triangles(s).reshape(-1, 3))
                            .reshape(-1, 3, 3))
                owner.append(np.full(len(tris[-1]), i, dtype=np.int64))
            self._static_root = self._forest.add(np.concatenate(tris), np.concatenate(owner))
        self._dyn_meshes = []
        for i, s in by_kind['mesh']:
            if not s.static:
                tris = _mesh_triangles(s)
                root = self._forest.add(tris, np.full(len(tris), i, dtype=np.int64))
                self._dyn_meshes.append((i, s, root))
        self._forest.freeze()

    def _excluded(self, exclude):
        if exclude is None:
            return None
        if callable(exclude):
            mask = np.fromiter((bool(exclude(s)) for s in self.shapes), dtype=bool,
                               count=len(self.shapes))
        else:
            ex = exclude if isinstance(exclude, (set, frozenset)) else set(exclude)
            mask = np.fromiter((p in ex for p in self._pairs), dtype=bool,
                               count=len(self.shapes))
        return mask if mask.any() else None

    def cast(self, origins, directions, max_range, exclude=None):
        """Distance (N,) along each unit direction to the first hit, np.inf where nothing is
        hit within max_range. origins (N, 3) or (3,), directions (N, 3), world frame.
        exclude: callable(shape) -> bool, or a set of (model, link) pairs to ignore."""
        return self.cast_hits(origins, directions, max_range, exclude)[0]

    def cast_hits(self, origins, directions, max_range, exclude=None):
        """As cast(), plus (N,) the index in self.shapes of the shape hit (-1 for none)."""
        o, d = _as_rays(origins, directions)
        n = len(d)
        best = np.full(n, float(max_range))
        who = np.full(n, -1, dtype=np.int64)
        if n == 0 or not max_range > 0:
            return np.full(n, np.inf), who
        excluded = self._excluded(exclude)
        for g in self._groups:
            t, k = g.hits(o, d, best, excluded)
            better = (k >= 0) & (t < best)
            if better.any():
                best = np.where(better, t, best)
                who = np.where(better, g.index[np.maximum(k, 0)], who)
        if not self._forest.empty:
            self._cast_meshes(o, d, best, who, excluded)
        dist = np.where(who >= 0, best, np.inf)
        return dist, who

    def _cast_meshes(self, o, d, best, who, excluded):
        n = len(d)
        frames_o, frames_d, ray_ids, roots = [o], [d], [], []
        base = np.arange(n)
        if self._static_root is not None:
            ray_ids.append(base)
            roots.append(np.full(n, self._static_root, dtype=np.int64))
        f = 0
        for i, s, root in self._dyn_meshes:
            if excluded is not None and excluded[i]:
                continue
            pose = s.world_pose()
            rot = pose.rotation()
            frames_o.append((o - pose.p) @ rot)
            frames_d.append(d @ rot)
            f += 1
            ray_ids.append(base + f * n)
            roots.append(np.full(n, root, dtype=np.int64))
        if not ray_ids:
            return
        oo = np.concatenate(frames_o)
        dd = np.concatenate(frames_d)
        limit = np.tile(best, f + 1)
        tri_ok = None
        if excluded is not None:
            tri_ok = ~excluded[self._forest.owner]
        t, k = self._forest.intersect(oo, dd, limit, np.concatenate(ray_ids),
                                      np.concatenate(roots), tri_ok)
        t = t.reshape(f + 1, n)
        k = k.reshape(f + 1, n)
        j = np.argmin(t, axis=0)
        tb = t[j, base]
        kb = k[j, base]
        better = (kb >= 0) & (tb < best)
        best[better] = tb[better]
        who[better] = kb[better]


def scan_directions(sensor_params):
    """Unit ray directions (N, 3) in the sensor frame, in Gazebo's order: for each vertical
    sample j (outer loop, pitch from v_min_angle to v_max_angle) each horizontal sample i
    (yaw from min_angle to max_angle, both ends included). A single sample points at angle 0
    (MultiRayShape::Init does so). The ray is the unit X axis rotated by
    Euler(0, -pitch, yaw), so positive pitch looks up. `samples` rays are cast; <resolution>
    only changes how many ranges are interpolated from them (laser.py)."""
    from .laser import scan_geometry
    return scan_geometry(sensor_params)['directions']
