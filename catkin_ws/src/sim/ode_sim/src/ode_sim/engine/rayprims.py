"""Ray casting primitives (see raycast.py for the semantics): rays as arrays, shape poses,
the exact ray tests per shape kind, and the azimuth fan that pairs the rays of one origin with
the bounds they may cross."""
import math

import numpy as np

from ode_sim.description.transforms import Pose

LEAF = 8        # triangles per BVH leaf (at most)
BRANCH = 8      # children per inner BVH node (at most): 3 levels of binary median splits
TOL = 1e-12


def as_rays(origins, directions):
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


def quat_matrices(q):
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


def pose_arrays(shapes):
    """World rotation matrices (K, 3, 3) and positions (K, 3) of shapes."""
    k = len(shapes)
    rot = np.empty((k, 3, 3))
    pos = np.empty((k, 3))
    for i, s in enumerate(shapes):
        pose = s.world_pose()
        rot[i] = pose.rotation()
        pos[i] = pose.p
    return rot, pos


class Posing:
    """World poses of dynamic shapes, fast: each distinct link_pose callable (equal bound
    methods count as one) is called once per cast and composed with the shapes' fixed local
    poses in one batch. A static shape among them (a group of one kind with static and dynamic
    shapes) keeps its static link pose."""

    def __init__(self, shapes):
        slot = {}
        self.calls = []
        idx = []
        for s in shapes:
            if s.link_pose is None:
                key = ('static', id(s))
                call = (lambda pose=s.static_pose: pose)
            else:
                key = call = s.link_pose            # bound methods of one link compare equal
                try:
                    hash(key)
                except TypeError:
                    key = ('id', id(key))
            if key not in slot:
                slot[key] = len(self.calls)
                self.calls.append(call)
            idx.append(slot[key])
        # a simulated link's pose() (engine.bodies.SimLink) is read from its ODE body in one
        # batch: position and quaternion; the link frame's fixed offset in the body frame is
        # folded into the shapes' local poses
        bodies, offsets, order = [], [], []
        generic = []
        for j, f in enumerate(self.calls):
            owner = getattr(f, '__self__', None)
            frame = getattr(owner, 'body_frame', None)
            src = frame() if getattr(f, '__name__', '') == 'pose' and callable(frame) else None
            if src is not None:
                bodies.append(src[0])
                offsets.append(src[1])
                order.append(j)
            else:
                generic.append(j)
        self.bodies = bodies
        self.generic = [self.calls[j] for j in generic]
        # link rows: bodies first, then the other callables; idx maps shapes to link rows
        row = {j: r for r, j in enumerate(order + generic)}
        self.idx = np.array([row[i] for i in idx], dtype=np.int64)
        off = offsets + [Pose()] * len(generic)
        off_rot = np.array([o.rotation() for o in off]).reshape(-1, 3, 3)[self.idx]
        off_pos = np.array([o.p for o in off]).reshape(-1, 3)[self.idx]
        local_rot = np.array([s.local.rotation() for s in shapes]).reshape(-1, 3, 3)
        local_pos = np.array([s.local.p for s in shapes]).reshape(-1, 3)
        # each shape's pose in its row's frame (the body's, or the link's for the others)
        self.local_rot = np.matmul(off_rot, local_rot)
        self.local_pos = off_pos + np.einsum('kij,kj->ki', off_rot, local_pos)

    def links(self):
        """The rows' poses now: unit quaternions (L, 4) x y z w and positions (L, 3)."""
        qs, ps = [], []
        if self.bodies:
            q = np.array([b.getQuaternion() for b in self.bodies])[:, (1, 2, 3, 0)]   # ODE: w x y z
            q /= np.sqrt(np.einsum('ij,ij->i', q, q))[:, None]
            qs.append(q)
            ps.append(np.array([b.getPosition() for b in self.bodies]))
        if self.generic:
            poses = [f() for f in self.generic]
            qs.append(np.array([p.q for p in poses]))
            ps.append(np.array([p.p for p in poses]))
        if len(qs) == 1:
            return qs[0], ps[0]
        return np.concatenate(qs), np.concatenate(ps)

    def __call__(self):
        """World rotations (K, 3, 3) and positions (K, 3) of the shapes now."""
        q, p = self.links()
        lrot = quat_matrices(q)[self.idx]
        rot = np.matmul(lrot, self.local_rot)
        pos = p[self.idx] + np.einsum('kij,kj->ki', lrot, self.local_pos)
        return rot, pos


def reduce_hits(t, ok):
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

def k_box(ox, oy, oz, dx, dy, dz, hx, hy, hz, tmin):
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


def k_sphere(ox, oy, oz, dx, dy, dz, r, tmin):
    """o relative to the centre."""
    b = ox * dx + oy * dy + oz * dz
    c = ox * ox + oy * oy + oz * oz - r * r
    disc = b * b - c
    sq = np.sqrt(np.maximum(disc, 0.0))
    t = -b - sq
    t = np.where(t >= tmin, t, -b + sq)               # start inside: the far root (as ODE)
    return t, (disc >= 0.0) & (t >= tmin)


def k_cylinder(ox, oy, oz, dx, dy, dz, r, hl, tmin):
    r2 = r * r
    tol_r = r2 * (1.0 + TOL) + 1e-15
    tol_z = hl * (1.0 + TOL) + 1e-15
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


def to_local(o, d, rot, pos):
    """Rays (N, 3) into K shape frames (local = R^T (x - p)): per-axis (K, N) arrays
    (ox, oy, oz), (dx, dy, dz)."""
    k = len(rot)
    m = rot.transpose(2, 0, 1).reshape(3 * k, 3)        # row i*K + k: column i of R_k
    shift = np.einsum('kji,kj->ik', rot, pos).reshape(-1)
    lo = (m @ o.T - shift[:, None]).reshape(3, k, -1)
    ld = (m @ d.T).reshape(3, k, -1)
    return lo, ld


def plane_hits(o, d, normal, offset, tmin):
    den = normal @ d.T                                # (K, N)
    num = offset[:, None] - normal @ o.T
    with np.errstate(divide='ignore', invalid='ignore'):
        t = num / den
    return t, (den != 0.0) & (t >= tmin)


def aabb(kind, rot, pos, geometry):
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


class Fan:
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
        pl, pos = expand(np.concatenate([m, m]), np.concatenate([s1, s2]),
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

def expand(ids, starts, counts):
    """For each i: ids[i] repeated counts[i] times, paired with starts[i] + 0..counts[i]-1."""
    total = int(counts.sum())
    if total == 0:
        return ids[:0], starts[:0]
    rep = np.repeat(ids, counts)
    offs = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    return rep, np.repeat(starts, counts) + offs


def first_per_ray(r, t, tri):
    """Among candidate hits (ray r, distance t, triangle or item tri): the nearest per ray;
    on a tie the lowest tri (the first in the caster's order, as the compiled core)."""
    order = np.lexsort((tri, t, r))
    r, t, tri = r[order], t[order], tri[order]
    first = np.ones(len(r), dtype=bool)
    first[1:] = r[1:] != r[:-1]
    return r[first], t[first], tri[first]


def record_hits(best, who, r, t, k, ok, owner):
    """Keep the candidate hits `ok` (ray r, distance t, triangle or item k) and write the
    nearest per ray into best (distance) and who (owner.take(k)); returns (best, who)."""
    r, t, k = r[ok], t[ok], k[ok]
    if len(r):
        r, t, k = first_per_ray(r, t, k)
        best[r] = t
        who[r] = owner.take(k)
    return best, who


def shape_params(items):
    """(K, 3) parameters of box / sphere / cylinder items [(index, shape)]: a box's half
    extents, else (radius, half length, 0)."""
    p = np.zeros((len(items), 3))
    for j, (_, s) in enumerate(items):
        g = s.geometry
        if g.kind == 'box':
            p[j] = np.asarray(g.size, dtype=float) / 2.0
        else:
            p[j, :2] = (float(g.radius), float(g.length) / 2.0)
    return p


def static_first(items):
    """[(index, shape)] with the static shapes first, each group in its order."""
    return [it for it in items if it[1].static] + [it for it in items if not it[1].static]
