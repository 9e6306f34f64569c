"""Mesh-building maths for the model library (scripts/make_models.py): closed triangle meshes
made of boxes and solids of revolution, written as deterministic binary STL, and the mass
properties of a model approximated by its collision primitives.

A `Part` is an indexed triangle mesh (vertices N x 3 float, faces M x 3 int) whose triangles are
wound counter-clockwise seen from outside (outward normals). Every primitive here is a closed
2-manifold, so a union of parts has every directed edge matched by its reverse: that is what
`edge_balance()` checks.
"""
import math
import struct

import numpy as np

from ode_sim.description.transforms import Pose

# STL coordinates are rounded to this many decimals (metres) before the float32 cast, so that
# last-bit differences of sin/cos between machines do not change the bytes written.
DECIMALS = 6


class Part:
    def __init__(self, vertices, faces):
        self.vertices = np.asarray(vertices, dtype=float).reshape(-1, 3)
        self.faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)

    def transformed(self, xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)):
        pose = Pose.from_xyz_rpy(list(xyz), list(rpy))
        return Part(pose.apply(self.vertices), self.faces)

    def scaled(self, sx, sy, sz):
        return _oriented(Part(self.vertices * np.array([sx, sy, sz]), self.faces))

    def triangles(self):
        return self.vertices[self.faces]

    def __len__(self):
        return len(self.faces)


def combine(parts):
    verts, faces, base = [], [], 0
    for part in parts:
        verts.append(part.vertices)
        faces.append(part.faces + base)
        base += len(part.vertices)
    if not verts:
        return Part(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))
    return Part(np.vstack(verts), np.vstack(faces))


def signed_volume(triangles):
    t = np.asarray(triangles, dtype=float)
    return float(np.einsum('ij,ij->i', t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)


def _oriented(part):
    """The same closed part with its faces wound so that the enclosed volume is positive."""
    if signed_volume(part.triangles()) < 0:
        return Part(part.vertices, part.faces[:, ::-1])
    return part


def box(size, center=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)):
    """An axis-aligned box of full extents `size`, then rotated by rpy and moved to center."""
    hx, hy, hz = (0.5 * float(s) for s in size)
    v = np.array([[sx * hx, sy * hy, sz * hz]
                  for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    # vertex index = 4*ix + 2*iy + iz
    f = [(0, 1, 3), (0, 3, 2),      # -x
         (4, 6, 7), (4, 7, 5),      # +x
         (0, 4, 5), (0, 5, 1),      # -y
         (2, 3, 7), (2, 7, 6),      # +y
         (0, 2, 6), (0, 6, 4),      # -z
         (1, 5, 7), (1, 7, 3)]      # +z
    return _oriented(Part(v, f)).transformed(center, rpy)


def box_between(lo, hi):
    """The axis-aligned box with opposite corners lo and hi."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    return box(hi - lo, (lo + hi) / 2)


def lathe(profile, segments=24):
    """Solid of revolution about Z of a closed polygon [(r, z), ...] (r >= 0; points with r == 0
    lie on the axis). The polygon must not cross itself."""
    if segments % 4:
        raise ValueError('lathe: segments must be a multiple of 4 (exact extents on x and y)')
    angles = 2 * math.pi * np.arange(segments) / segments
    # exact values where they are known, so that the extents are exactly the radius
    cos, sin = np.cos(angles), np.sin(angles)
    q = segments // 4
    cos[[0, q, 2 * q, 3 * q]] = [1.0, 0.0, -1.0, 0.0]
    sin[[0, q, 2 * q, 3 * q]] = [0.0, 1.0, 0.0, -1.0]
    verts, index = [], []
    for r, z in profile:
        if r < 0:
            raise ValueError('lathe: negative radius in profile')
        if r == 0:
            index.append(len(verts))
            verts.append((0.0, 0.0, z))
        else:
            index.append(len(verts))
            verts.extend((r * c, r * s, z) for c, s in zip(cos, sin))
    faces = []
    m = len(profile)
    for i in range(m):
        j = (i + 1) % m
        ri, rj = profile[i][0], profile[j][0]
        for k in range(segments):
            k1 = (k + 1) % segments
            if ri > 0 and rj > 0:
                a, b = index[i] + k, index[i] + k1
                c, d = index[j] + k1, index[j] + k
                faces.append((a, b, c))
                faces.append((a, c, d))
            elif ri > 0:
                faces.append((index[i] + k, index[i] + k1, index[j]))
            elif rj > 0:
                faces.append((index[i], index[j] + k1, index[j] + k))
    return _oriented(Part(verts, faces))


def cylinder(radius, length, center=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0), segments=24):
    """A cylinder along local Z centred on `center` (as SDF's <cylinder>)."""
    h = 0.5 * length
    return lathe([(0.0, -h), (radius, -h), (radius, h), (0.0, h)], segments).transformed(
        center, rpy)


def frustum(r_bottom, r_top, z_bottom, z_top, segments=24):
    """A truncated cone about Z between two heights (r_top may be 0: a cone)."""
    return lathe([(0.0, z_bottom), (r_bottom, z_bottom), (r_top, z_top), (0.0, z_top)],
                 segments)


def ring(r_in, r_out, z_bottom, z_top, segments=24):
    """A flat annulus (a hoop) about Z."""
    return lathe([(r_in, z_bottom), (r_out, z_bottom), (r_out, z_top), (r_in, z_top)], segments)


def ellipsoid(radii, center=(0.0, 0.0, 0.0), segments=16, rings=8):
    """An ellipsoid with semi-axes radii (rx, ry, rz)."""
    prof = [(math.sin(math.pi * i / rings), -math.cos(math.pi * i / rings))
            for i in range(rings + 1)]
    prof[0] = (0.0, -1.0)
    prof[-1] = (0.0, 1.0)
    unit = lathe(prof, segments)
    return unit.scaled(*radii).transformed(center)


def quantized_triangles(part):
    tri = np.round(part.triangles(), DECIMALS) + 0.0     # + 0.0: no negative zeros
    return tri.astype(np.float32)


def stl_bytes(part, name):
    """Binary STL of the part: 80-byte header naming it, count, one record per triangle with its
    unit normal. No time stamp, so the same part always gives the same bytes."""
    tri = quantized_triangles(part)
    t64 = tri.astype(np.float64)
    n = np.cross(t64[:, 1] - t64[:, 0], t64[:, 2] - t64[:, 0])
    length = np.linalg.norm(n, axis=1)
    length[length == 0] = 1.0
    n = (n / length[:, None]).astype(np.float32)
    rec = np.zeros(len(tri), dtype=np.dtype([('normal', '<f4', (3,)), ('vectors', '<f4', (3, 3)),
                                             ('attr', '<u2')]))
    rec['normal'] = n
    rec['vectors'] = tri
    header = ('ode_sim model library: %s' % name).encode('ascii')[:80].ljust(80, b' ')
    return header + struct.pack('<I', len(tri)) + rec.tobytes()


def edge_balance(triangles, decimals=5):
    """Number of directed edges not matched by the reverse edge of another triangle (0 for a
    closed, consistently wound mesh or a union of such meshes)."""
    t = np.round(np.asarray(triangles, dtype=float), decimals) + 0.0
    counts = {}
    for tri in t:
        pts = [tuple(p) for p in tri]
        for a, b in ((0, 1), (1, 2), (2, 0)):
            key = (pts[a], pts[b])
            counts[key] = counts.get(key, 0) + 1
    unmatched = 0
    for (a, b), c in counts.items():
        unmatched += abs(c - counts.get((b, a), 0))
    return unmatched // 2 if unmatched % 2 == 0 else unmatched


# ---------------------------------------------------------------- mass properties

def primitive_volume(kind, dims):
    if kind == 'box':
        return float(dims[0] * dims[1] * dims[2])
    if kind == 'cylinder':
        return math.pi * dims[0] ** 2 * dims[1]
    if kind == 'sphere':
        return 4.0 / 3.0 * math.pi * dims[0] ** 3
    raise ValueError('unknown primitive %r' % kind)


def primitive_inertia(kind, dims, mass):
    """Inertia tensor about the primitive's centre, in its own frame (cylinder along Z)."""
    if kind == 'box':
        x, y, z = dims
        return mass / 12.0 * np.diag([y * y + z * z, x * x + z * z, x * x + y * y])
    if kind == 'cylinder':
        r, h = dims
        i = mass * (3 * r * r + h * h) / 12.0
        return np.diag([i, i, 0.5 * mass * r * r])
    if kind == 'sphere':
        return np.eye(3) * 0.4 * mass * dims[0] ** 2
    raise ValueError('unknown primitive %r' % kind)


def composite_inertia(mass, prims):
    """Mass properties of a body of total `mass` spread over primitives.

    prims: iterable of (kind, dims, xyz, rpy, weight): box dims (x, y, z), cylinder (r, length),
    sphere (r,); weight is a relative density. Returns (com xyz, 3x3 inertia about the com in
    the body frame)."""
    prims = list(prims)
    wv = np.array([primitive_volume(k, d) * w for k, d, _, _, w in prims])
    masses = mass * wv / wv.sum()
    centres = np.array([p[2] for p in prims], dtype=float)
    com = (masses[:, None] * centres).sum(axis=0) / mass
    inertia = np.zeros((3, 3))
    for (kind, dims, xyz, rpy, _), m in zip(prims, masses):
        rot = Pose.from_xyz_rpy(list(xyz), list(rpy)).matrix()[:3, :3]
        d = np.asarray(xyz, dtype=float) - com
        inertia += rot @ primitive_inertia(kind, dims, m) @ rot.T
        inertia += m * (d.dot(d) * np.eye(3) - np.outer(d, d))
    return com, inertia
