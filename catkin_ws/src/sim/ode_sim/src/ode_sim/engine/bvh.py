"""The meshes' bounding-volume hierarchies for ray casting (raycast.py): one wide BVH forest
in which each mesh (or all static meshes together) is a tree of triangle leaves."""
import math

import numpy as np

from ode_sim.description.model import ModelError
from ode_sim.engine.rayprims import BRANCH, LEAF, TOL, expand, record_hits


class BVHForest:
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
            if depth == 0 or e - s <= LEAF:
                return [(s, e)]
            idx = perm[s:e]
            c = cent[idx]
            axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
            perm[s:e] = idx[np.argsort(c[:, axis], kind='stable')]
            m = (s + e) // 2
            return split(s, m, depth - 1) + split(m, e, depth - 1)

        levels = int(round(math.log2(BRANCH)))
        i = 0
        while i < len(ranges):                      # breadth first: siblings are contiguous
            s, e = ranges[i]
            if e - s > LEAF:
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
            ok = (u >= -TOL) & (v >= -TOL) & (u + v <= 1.0 + TOL) & (det != 0.0)
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
            pr, pn = expand(pr, self.first.take(pn), self.count.take(pn))
        if not leaf_r:
            return best, who
        ln = np.concatenate(leaf_n)
        r, tri = expand(np.concatenate(leaf_r), self.first.take(ln), self.count.take(ln))
        r, tri = _allowed(r, tri, tri_ok)
        t, ok = self._triangles(ro[0].take(r), ro[1].take(r), ro[2].take(r),
                                rd[0].take(r), rd[1].take(r), rd[2].take(r), tri)
        ok &= (t >= tmin) & (t <= limit.take(r))
        return record_hits(best, who, r, t, tri, ok, self.owner)

    # -- rays from one origin: leaves culled by distance and azimuth ---------------------------
    def intersect_common(self, fan, tmin, limit, leaves, tri_ok=None):
        """Rays of a Fan (one origin) with per-ray limit (N,) against the triangles under the
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
        r, tri = expand(pr, self.first.take(pl), self.count.take(pl))
        r, tri = _allowed(r, tri, tri_ok)
        cx, cy, cz = fan.c
        dx, dy, dz = fan.d
        t, ok = self._triangles(cx, cy, cz, dx.take(r), dy.take(r), dz.take(r), tri)
        ok &= (t >= tmin) & (t <= limit.take(r))
        return record_hits(best, who, r, t, tri, ok, self.owner)


def _allowed(r, tri, tri_ok):
    """Candidate (ray, triangle) pairs without the triangles tri_ok excludes (None: all)."""
    if tri_ok is None:
        return r, tri
    keep = tri_ok.take(tri)
    return r[keep], tri[keep]


def mesh_triangles(shape):
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
