"""Ray casting against the simulator's collision shapes, vectorised with numpy.

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
  * Hits count when min_range <= distance <= max_range.

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
import math

import numpy as np

from ode_sim.description.model import ModelError

KINDS = ('box', 'sphere', 'cylinder', 'plane', 'mesh')

_LEAF = 8        # triangles per BVH leaf (at most)
_BRANCH = 8      # children per inner BVH node (at most): 3 levels of binary median splits
_TOL = 1e-12



def _as_rays(origins, directions):
    """(origins (N, 3), directions (N, 3), common origin (3,) or None)."""
    d = np.asarray(directions, dtype=float)
    if d.ndim == 1:
        d = d.reshape(1, 3)
    if d.ndim != 2 or d.shape[1] != 3:
        raise ValueError('directions must be (N, 3), got shape %s' % (d.shape,))
    norm = np.sqrt(np.einsum('ij,ij->i', d, d))
    if len(d) and not np.all(np.abs(norm - 1.0) < 1e-9):
        if not np.all(norm > 0) or not np.all(np.isfinite(norm)):
            raise ValueError('directions must be non-zero finite vectors')
        d = d / norm[:, None]                       # distances stay distances
    o = np.asarray(origins, dtype=float)
    common = None
    if o.ndim == 1:
        if o.shape != (3,):
            raise ValueError('origins must be (3,) or (N, 3), got shape %s' % (o.shape,))
        common = o
        o = np.broadcast_to(o, d.shape)
    elif o.shape != d.shape:
        raise ValueError('origins %s and directions %s differ in shape' % (o.shape, d.shape))
    elif len(o) and np.all(o == o[0]):
        common = o[0]
    return o, np.ascontiguousarray(d), common


def _quat_matrices(q):
    """Rotation matrices (K, 3, 3) of unit quaternions (K, 4) x, y, z, w."""
    x, y, z, w = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    m = np.empty((len(q), 3, 3))
    m[:, 0, 0] = 1 - 2 * (y * y + z * z)
    m[:, 0, 1] = 2 * (x * y - z * w)
    m[:, 0, 2] = 2 * (x * z + y * w)
    m[:, 1, 0] = 2 * (x * y + z * w)
    m[:, 1, 1] = 1 - 2 * (x * x + z * z)
    m[:, 1, 2] = 2 * (y * z - x * w)
    m[:, 2, 0] = 2 * (x * z - y * w)
    m[:, 2, 1] = 2 * (y * z + x * w)
    m[:, 2, 2] = 1 - 2 * (x * x + y * y)
    return m


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


class _Posing:
    """World poses of dynamic shapes, fast: each distinct link_pose callable (equal bound
    methods count as one) is called once per cast and composed with the shapes' fixed local
    poses in one batch."""

    def __init__(self, shapes):
        slot = {}
        self.calls = []
        idx = []
        for s in shapes:
            key = s.link_pose                       # bound methods of one link compare equal
            try:
                hash(key)
            except TypeError:
                key = ('id', id(key))
            if key not in slot:
                slot[key] = len(self.calls)
                self.calls.append(s.link_pose)
            idx.append(slot[key])
        self.idx = np.array(idx, dtype=np.int64)
        self.local_rot = np.array([s.local.rotation() for s in shapes]).reshape(-1, 3, 3)
        self.local_pos = np.array([s.local.p for s in shapes]).reshape(-1, 3)

    def __call__(self):
        poses = [f() for f in self.calls]
        lrot = _quat_matrices(np.array([p.q for p in poses]))[self.idx]
        lpos = np.array([p.p for p in poses])[self.idx]
        rot = np.matmul(lrot, self.local_rot)
        pos = lpos + np.einsum('kij,kj->ki', lrot, self.local_pos)
        return rot, pos


def _reduce_hits(t, ok):
    """t, ok: (K, N). Per ray: nearest valid t and the row it came from (-1 when none)."""
    t = np.where(ok, t, np.inf)
    k = np.argmin(t, axis=0)
    best = t[k, np.arange(t.shape[1])]
    k[~np.isfinite(best)] = -1
    return best, k


# ---------------------------------------------------------------------------------------------
# analytic shapes. Kernels take ray components in the shape frame and shape parameters that
# broadcast against them: (K, N) rays x shapes when tested densely, (P,) (ray, shape) pairs
# when culled first. They return (t, ok): the first surface crossing at t >= tmin.

def _k_box(ox, oy, oz, dx, dy, dz, hx, hy, hz, tmin):
    tn = tf = None
    with np.errstate(divide='ignore', invalid='ignore'):
        for o_, d_, h in ((ox, dx, hx), (oy, dy, hy), (oz, dz, hz)):
            inv = 1.0 / d_
            t1 = (-h - o_) * inv
            t2 = (h - o_) * inv
            # fmin/fmax skip the NaN of a ray lying in a slab's boundary plane (0 * inf)
            a, b = np.fmin(t1, t2), np.fmax(t1, t2)
            tn = a if tn is None else np.fmax(tn, a)
            tf = b if tf is None else np.fmin(tf, b)
    t = np.where(tn >= tmin, tn, tf)                  # start inside: the exit point (as ODE)
    return t, (tn <= tf) & (t >= tmin)


def _k_sphere(ox, oy, oz, dx, dy, dz, r, tmin):
    """o relative to the centre."""
    b = ox * dx + oy * dy + oz * dz
    c = ox * ox + oy * oy + oz * oz - r * r
    disc = b * b - c
    sq = np.sqrt(np.maximum(disc, 0.0))
    t = -b - sq
    t = np.where(t >= tmin, t, -b + sq)               # start inside: the far root (as ODE)
    return t, (disc >= 0.0) & (t >= tmin)


def _k_cylinder(ox, oy, oz, dx, dy, dz, r, hl, tmin):
    r2 = r * r
    tol_r = r2 * (1.0 + _TOL) + 1e-15
    tol_z = hl * (1.0 + _TOL) + 1e-15
    a = dx * dx + dy * dy
    b = ox * dx + oy * dy
    c = ox * ox + oy * oy - r2
    disc = b * b - a * c
    sq = np.sqrt(np.maximum(disc, 0.0))
    side_ok = (disc >= 0.0) & (a > 1e-300)
    best = np.full(np.broadcast(a, hl).shape, np.inf)
    with np.errstate(divide='ignore', invalid='ignore'):
        for t in ((-b - sq) / a, (-b + sq) / a):
            z = oz + t * dz
            good = side_ok & (t >= tmin) & (np.abs(z) <= tol_z) & (t < best)
            best = np.where(good, t, best)
        for zc in (hl, -hl):
            t = (zc - oz) / dz
            x = ox + t * dx
            y = oy + t * dy
            good = (t >= tmin) & (x * x + y * y <= tol_r) & (t < best)
            best = np.where(good, t, best)
    return best, np.isfinite(best)


def _to_local(o, d, rot, pos):
    """Rays (N, 3) into K shape frames (local = R^T (x - p)): per-axis (K, N) arrays
    (ox, oy, oz), (dx, dy, dz)."""
    k = len(rot)
    m = rot.transpose(2, 0, 1).reshape(3 * k, 3)        # row i*K + k: column i of R_k
    shift = np.einsum('kji,kj->ik', rot, pos).reshape(-1)
    lo = (m @ o.T - shift[:, None]).reshape(3, k, -1)
    ld = (m @ d.T).reshape(3, k, -1)
    return lo, ld


def _plane_hits(o, d, normal, offset, tmin):
    den = normal @ d.T                                # (K, N)
    num = offset[:, None] - normal @ o.T
    with np.errstate(divide='ignore', invalid='ignore'):
        t = num / den
    return t, (den != 0.0) & (t >= tmin)


def _aabb(kind, rot, pos, geometry):
    """World axis-aligned bounds (lo, hi) of a box, sphere or cylinder."""
    if kind == 'box':
        ext = np.abs(rot) @ (np.asarray(geometry.size, dtype=float) / 2.0)
    elif kind == 'sphere':
        ext = np.full(3, float(geometry.radius))
    else:
        axis = rot[:, 2]
        ext = (geometry.length / 2.0) * np.abs(axis) \
            + geometry.radius * np.sqrt(np.maximum(1.0 - axis * axis, 0.0))
    pad = 1e-9 * (1.0 + np.abs(pos).max() + ext.max())
    return pos - ext - pad, pos + ext + pad


class _Fan:
    """Rays from one origin, sorted by azimuth, to find which rays may cross which boxes."""

    def __init__(self, c, d):
        self.c = [float(c[0]), float(c[1]), float(c[2])]
        self.d = [np.ascontiguousarray(d[:, i]) for i in range(3)]
        with np.errstate(divide='ignore'):
            self.inv = [1.0 / x for x in self.d]
        az = np.arctan2(self.d[1], self.d[0])
        self.order = np.argsort(az, kind='stable')
        self.az = az[self.order]
        self.n = len(d)

    def candidates(self, lo, hi, tmin, limit):
        """Boxes given by per-axis bounds lo, hi (each (M,)): the (box, ray) pairs whose ray
        crosses the box at some t in [tmin, limit[ray]]. Boxes farther than any limit are
        dropped first; then each box's footprint in the XY plane subtends an azimuth interval
        (under pi, unless the origin lies over the footprint: then all rays), found among the
        sorted rays by bisection; the pairs left get a slab test."""
        n = self.n
        lx, ly, lz = (lo[i] - self.c[i] for i in range(3))
        hx, hy, hz = (hi[i] - self.c[i] for i in range(3))
        gx = np.maximum(np.maximum(lx, -hx), 0.0)
        gy = np.maximum(np.maximum(ly, -hy), 0.0)
        gz = np.maximum(np.maximum(lz, -hz), 0.0)
        near = np.flatnonzero(gx * gx + gy * gy + gz * gz <= float(limit.max()) ** 2)
        empty = np.zeros(0, dtype=np.int64)
        if len(near) == 0:
            return empty, empty
        lx, ly, lz, hx, hy, hz, gx, gy = (a.take(near) for a in (lx, ly, lz, hx, hy, hz, gx, gy))
        over = (gx == 0.0) & (gy == 0.0)
        mx, my = 0.5 * (lx + hx), 0.5 * (ly + hy)
        span_lo = span_hi = None
        for px in (lx, hx):
            for py in (ly, hy):
                a = np.arctan2(mx * py - my * px, mx * px + my * py)   # corner vs centre
                span_lo = a if span_lo is None else np.minimum(span_lo, a)
                span_hi = a if span_hi is None else np.maximum(span_hi, a)
        centre = np.arctan2(my, mx)
        pi, two_pi = math.pi, 2.0 * math.pi
        a0 = centre + span_lo - 1e-9
        a1 = centre + span_hi + 1e-9
        s1 = np.searchsorted(self.az, np.maximum(a0, -pi), 'left')
        e1 = np.searchsorted(self.az, np.minimum(a1, pi), 'right')
        wrap_lo, wrap_hi = a0 < -pi, a1 > pi        # the part past -pi / +pi
        s2 = np.where(wrap_lo, np.searchsorted(self.az, a0 + two_pi, 'left'), 0)
        e2 = np.where(wrap_lo, n, 0)
        e2 = np.where(wrap_hi, np.searchsorted(self.az, a1 - two_pi, 'right'), e2)
        everything = over | (wrap_lo & wrap_hi)
        s1 = np.where(everything, 0, s1)
        e1 = np.where(everything, n, e1)
        e2 = np.where(everything, 0, e2)
        m = np.arange(len(near))
        pl, pos = _expand(np.concatenate([m, m]), np.concatenate([s1, s2]),
                          np.concatenate([np.maximum(e1 - s1, 0), np.maximum(e2 - s2, 0)]))
        if len(pl) == 0:
            return empty, empty
        pr = self.order.take(pos)
        tn = tf = None
        with np.errstate(invalid='ignore'):
            for lo_, hi_, iv in ((lx, hx, self.inv[0]), (ly, hy, self.inv[1]),
                                 (lz, hz, self.inv[2])):
                ivp = iv.take(pr)
                t1 = lo_.take(pl) * ivp
                t2 = hi_.take(pl) * ivp
                a, b = np.fmin(t1, t2), np.fmax(t1, t2)
                tn = a if tn is None else np.fmax(tn, a)
                tf = b if tf is None else np.fmin(tf, b)
        keep = (tn <= tf) & (tf >= tmin) & (tn <= limit.take(pr))
        return near.take(pl[keep]), pr[keep]


# ---------------------------------------------------------------------------------------------
# triangle sets: a wide BVH per set, all sets in shared flat arrays (structure of arrays)

def _expand(ids, starts, counts):
    """For each i: ids[i] repeated counts[i] times, paired with starts[i] + 0..counts[i]-1."""
    total = int(counts.sum())
    if total == 0:
        return ids[:0], starts[:0]
    rep = np.repeat(ids, counts)
    offs = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    return rep, np.repeat(starts, counts) + offs


def _first_per_ray(r, t, tri):
    """Among candidate hits (ray r, distance t, triangle tri): the nearest per ray."""
    order = np.lexsort((t, r))
    r, t, tri = r[order], t[order], tri[order]
    first = np.ones(len(r), dtype=bool)
    first[1:] = r[1:] != r[:-1]
    return r[first], t[first], tri[first]


class _BVHForest:
    """Triangle sets, each with its own hierarchy (root), stored in shared flat arrays."""

    def __init__(self):
        self._parts = []
        self.roots = []
        self._ntri = 0
        self._nnode = 0
        self.empty = True

    def add(self, tris, owner):
        """Build the hierarchy of tris (T, 3, 3) whose triangle i belongs to shape owner[i];
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

        levels = int(round(math.log2(_BRANCH)))
        i = 0
        while i < len(ranges):                      # breadth first: siblings are contiguous
            s, e = ranges[i]
            if e - s > _LEAF:
                kids = split(s, e, levels)
                first[i] = len(ranges)
                count[i] = len(kids)
                leaf[i] = False
                ranges.extend(kids)
                first.extend([0] * len(kids))
                count.extend([0] * len(kids))
                leaf.extend([True] * len(kids))
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
        pad = 1e-9 * (1.0 + max(np.abs(lo).max(), np.abs(hi).max()))
        self._parts.append((lo - pad, hi + pad, first, count, leaf, tris, owner))
        root = self._nnode
        self.roots.append((root, root + m))
        self._nnode += m
        self._ntri += n
        return root

    def freeze(self):
        if not self._parts:
            return self
        self.empty = False
        cols = list(zip(*self._parts))
        lo, hi = np.concatenate(cols[0]), np.concatenate(cols[1])
        self.lo = [np.ascontiguousarray(lo[:, i]) for i in range(3)]
        self.hi = [np.ascontiguousarray(hi[:, i]) for i in range(3)]
        self.first = np.concatenate([np.asarray(c, dtype=np.int64) for c in cols[2]])
        self.count = np.concatenate([np.asarray(c, dtype=np.int64) for c in cols[3]])
        self.leaf = np.concatenate([np.asarray(c, dtype=bool) for c in cols[4]])
        tris = np.concatenate(cols[5])
        self.owner = np.concatenate(cols[6])
        e1 = tris[:, 1] - tris[:, 0]
        e2 = tris[:, 2] - tris[:, 0]
        self.v0 = [np.ascontiguousarray(tris[:, 0, i]) for i in range(3)]
        self.e1 = [np.ascontiguousarray(e1[:, i]) for i in range(3)]
        self.e2 = [np.ascontiguousarray(e2[:, i]) for i in range(3)]
        del self._parts
        return self

    def leaves_of(self, root):
        """Leaf node indices of the hierarchy rooted at root."""
        for r, end in self.roots:
            if r == root:
                return r + np.flatnonzero(self.leaf[r:end])
        raise KeyError(root)

    # -- Moller-Trumbore on (ray, triangle) pairs ---------------------------------------------
    def _triangles(self, ox, oy, oz, dx, dy, dz, tri):
        """t and validity of rays (per-axis arrays, or scalars for a shared origin) against
        triangles tri (same length as the direction arrays)."""
        v0, e1, e2 = self.v0, self.e1, self.e2
        ax, ay, az = e1[0].take(tri), e1[1].take(tri), e1[2].take(tri)
        bx, by, bz = e2[0].take(tri), e2[1].take(tri), e2[2].take(tri)
        px = dy * bz - dz * by                          # p = d x e2
        py = dz * bx - dx * bz
        pz = dx * by - dy * bx
        det = ax * px + ay * py + az * pz
        tx = ox - v0[0].take(tri)
        ty = oy - v0[1].take(tri)
        tz = oz - v0[2].take(tri)
        qx = ty * az - tz * ay                          # q = (o - v0) x e1
        qy = tz * ax - tx * az
        qz = tx * ay - ty * ax
        with np.errstate(divide='ignore', invalid='ignore'):
            inv = 1.0 / det
            u = (tx * px + ty * py + tz * pz) * inv
            v = (dx * qx + dy * qy + dz * qz) * inv
            t = (bx * qx + by * qy + bz * qz) * inv
            ok = (u >= -_TOL) & (v >= -_TOL) & (u + v <= 1.0 + _TOL) & (det != 0.0)
        return t, ok

    # -- rays with their own origins: breadth-first walk of the hierarchies --------------------
    def intersect(self, o, d, tmin, limit, ray_ids, roots, tri_ok=None):
        """Rays o, d (R, 3), per-ray limit (R,); initial (ray, root) pairs ray_ids, roots.
        Returns per ray the nearest t >= tmin (inf if none) and the owner hit (-1)."""
        nray = len(o)
        best = np.full(nray, np.inf)
        who = np.full(nray, -1, dtype=np.int64)
        if self.empty or len(ray_ids) == 0:
            return best, who
        ro = [np.ascontiguousarray(o[:, i]) for i in range(3)]
        rd = [np.ascontiguousarray(d[:, i]) for i in range(3)]
        with np.errstate(divide='ignore'):
            inv = [1.0 / x for x in rd]
        pr, pn = ray_ids, roots
        leaf_r, leaf_n = [], []
        while len(pr):
            tn = tf = None
            with np.errstate(invalid='ignore'):
                for i in range(3):
                    oi, iv = ro[i].take(pr), inv[i].take(pr)
                    t1 = (self.lo[i].take(pn) - oi) * iv
                    t2 = (self.hi[i].take(pn) - oi) * iv
                    a, b = np.fmin(t1, t2), np.fmax(t1, t2)
                    tn = a if tn is None else np.fmax(tn, a)
                    tf = b if tf is None else np.fmin(tf, b)
            keep = (tn <= tf) & (tf >= tmin) & (tn <= limit.take(pr))
            pr, pn = pr[keep], pn[keep]
            is_leaf = self.leaf.take(pn)
            if is_leaf.any():
                leaf_r.append(pr[is_leaf])
                leaf_n.append(pn[is_leaf])
                inner = ~is_leaf
                pr, pn = pr[inner], pn[inner]
            pr, pn = _expand(pr, self.first.take(pn), self.count.take(pn))
        if not leaf_r:
            return best, who
        ln = np.concatenate(leaf_n)
        r, tri = _expand(np.concatenate(leaf_r), self.first.take(ln), self.count.take(ln))
        if tri_ok is not None:
            keep = tri_ok.take(tri)
            r, tri = r[keep], tri[keep]
        t, ok = self._triangles(ro[0].take(r), ro[1].take(r), ro[2].take(r),
                                rd[0].take(r), rd[1].take(r), rd[2].take(r), tri)
        ok &= (t >= tmin) & (t <= limit.take(r))
        r, t, tri = r[ok], t[ok], tri[ok]
        if len(r):
            r, t, tri = _first_per_ray(r, t, tri)
            best[r] = t
            who[r] = self.owner.take(tri)
        return best, who

    # -- rays from one origin: leaves culled by distance and azimuth ---------------------------
    def intersect_common(self, fan, tmin, limit, leaves, tri_ok=None):
        """Rays of a _Fan (one origin) with per-ray limit (N,) against the triangles under the
        given leaves. Same result as intersect()."""
        n = fan.n
        best = np.full(n, np.inf)
        who = np.full(n, -1, dtype=np.int64)
        if self.empty or n == 0 or len(leaves) == 0:
            return best, who
        lo = [a.take(leaves) for a in self.lo]
        hi = [a.take(leaves) for a in self.hi]
        pl, pr = fan.candidates(lo, hi, tmin, limit)
        pl = leaves.take(pl)
        r, tri = _expand(pr, self.first.take(pl), self.count.take(pl))
        if tri_ok is not None:
            keep = tri_ok.take(tri)
            r, tri = r[keep], tri[keep]
        cx, cy, cz = fan.c
        dx, dy, dz = fan.d
        t, ok = self._triangles(cx, cy, cz, dx.take(r), dy.take(r), dz.take(r), tri)
        ok &= (t >= tmin) & (t <= limit.take(r))
        r, t, tri = r[ok], t[ok], tri[ok]
        if len(r):
            r, t, tri = _first_per_ray(r, t, tri)
            best[r] = t
            who[r] = self.owner.take(tri)
        return best, who


def _mesh_triangles(shape):
    g = shape.geometry
    name = g.uri or g.filename or 'mesh'
    if g.vertices is None or g.faces is None or len(g.faces) == 0:
        raise ModelError('%s: mesh %r has no triangles loaded (vertices/faces missing)'
                         % (shape.key, name))
    v = np.asarray(g.vertices, dtype=float)
    f = np.asarray(g.faces, dtype=np.int64)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise ModelError('%s: mesh %r needs (N, 3) vertices and (M, 3) faces, got %s and %s'
                         % (shape.key, name, v.shape, f.shape))
    if f.min() < 0 or f.max() >= len(v):
        raise ModelError('%s: mesh %r has face indices outside its %d vertices'
                         % (shape.key, name, len(v)))
    return v[f]                                       # (M, 3, 3) in the shape frame


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
            self._posing = _Posing(self.shapes)

    def _pose(self):
        rot, pos = _pose_arrays(self.shapes) if self.static else self._posing()
        if self.kind == 'plane':
            n = np.einsum('kij,kj->ki', rot, self.local_normal)
            return n, np.einsum('ki,ki->k', n, pos)
        return rot, pos

    def hits(self, o, d, tmin, limit, excluded):
        a, b = self._posed if self.static else self._pose()
        if self.kind == 'plane':
            t, ok = _plane_hits(o, d, a, b, tmin)
        elif self.kind == 'sphere':
            oc = [o[:, i] - b[:, i, None] for i in range(3)]
            t, ok = _k_sphere(*oc, d[:, 0], d[:, 1], d[:, 2], self.radius[:, None], tmin)
        else:
            (ox, oy, oz), (dx, dy, dz) = _to_local(o, d, a, b)
            if self.kind == 'box':
                h = self.half
                t, ok = _k_box(ox, oy, oz, dx, dy, dz, h[:, 0, None], h[:, 1, None],
                               h[:, 2, None], tmin)
            else:
                t, ok = _k_cylinder(ox, oy, oz, dx, dy, dz, self.radius[:, None],
                                    self.half_len[:, None], tmin)
        ok &= t <= limit
        if excluded is not None:
            ok &= ~excluded[self.index][:, None]
        return _reduce_hits(t, ok)


class _Items:
    """Boxes, spheres and cylinders with world bounds, for rays from one origin: only the
    (ray, shape) pairs that survive _Fan.candidates are tested. Static ones are posed once,
    dynamic ones on every cast."""

    CODES = {'box': 0, 'sphere': 1, 'cylinder': 2}

    def __init__(self, items):
        items = [it for it in items if it[1].static] + [it for it in items if not it[1].static]
        self.index = np.array([i for i, _ in items], dtype=np.int64)
        self.code = np.array([self.CODES[s.geometry.kind] for _, s in items], dtype=np.int64)
        self.dynamic = [s for _, s in items if not s.static]
        self.nstatic = len(items) - len(self.dynamic)
        p1 = np.zeros((len(items), 3))              # box: half extents; others: radius, half len
        for j, (_, s) in enumerate(items):
            g = s.geometry
            if g.kind == 'box':
                p1[j] = np.asarray(g.size, dtype=float) / 2.0
            else:
                p1[j, :2] = (float(g.radius), float(g.length) / 2.0)
        self.p1 = p1
        self.p1_soa = [np.ascontiguousarray(p1[:, i]) for i in range(3)]
        self._static = self._posed(*_pose_arrays([s for _, s in items[:self.nstatic]]),
                                   slice(0, self.nstatic))
        self._posing = _Posing(self.dynamic) if self.dynamic else None

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
        for c, kernel, nparam in ((0, _k_box, 3), (1, _k_sphere, 1), (2, _k_cylinder, 2)):
            sel = np.flatnonzero(code == c)
            if len(sel) == 0:
                continue
            args = [a.take(sel) for a in (ox, oy, oz, dx, dy, dz)] + \
                [a.take(sel) for a in p[:nparam]]
            t[sel], ok[sel] = kernel(*args, tmin)
        ok &= t <= limit.take(r)
        r, t, k = r[ok], t[ok], k[ok]
        if len(r):
            r, t, k = _first_per_ray(r, t, k)
            best[r] = t
            who[r] = self.index.take(k)
        return best, who


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
        # analytic shapes: dense groups, static and dynamic apart; the static solids also as
        # items culled per ray fan
        self._groups = [_Group(k, by_kind[k]) for k in ('box', 'sphere', 'cylinder', 'plane')
                        if by_kind[k]]
        self._planes = [g for g in self._groups if g.kind == 'plane']
        items = by_kind['box'] + by_kind['sphere'] + by_kind['cylinder']
        self._items = _Items(items) if items else None
        # meshes: all static ones in one world-frame hierarchy, each dynamic one in its own
        self._forest = _BVHForest()
        self._static_root = None
        static = [(i, s) for i, s in by_kind['mesh'] if s.static]
        if static:
            tris = np.concatenate([s.world_pose().apply(_mesh_triangles(s).reshape(-1, 3))
                                   .reshape(-1, 3, 3) for _, s in static])
            owner = np.concatenate([np.full(len(s.geometry.faces), i, dtype=np.int64)
                                    for i, s in static])
            self._static_root = self._forest.add(tris, owner)
        self._dyn_meshes = []
        for i, s in by_kind['mesh']:
            if not s.static:
                tris = _mesh_triangles(s)
                root = self._forest.add(tris, np.full(len(tris), i, dtype=np.int64))
                self._dyn_meshes.append((i, s, root))
        self._forest.freeze()
        self._static_leaves = (self._forest.leaves_of(self._static_root)
                               if self._static_root is not None else None)

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
        o, d, common = _as_rays(origins, directions)
        n = len(d)
        tmin = max(float(min_range), 0.0)
        best = np.full(n, float(max_range))
        who = np.full(n, -1, dtype=np.int64)
        if n == 0 or not max_range >= tmin:
            return np.full(n, np.inf), who
        excluded = self._excluded(exclude)
        fan = _Fan(common, d) if common is not None else None

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
