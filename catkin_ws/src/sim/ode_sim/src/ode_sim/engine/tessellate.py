"""Triangle meshes of the primitive geometries, in the shape's own frame, for the renderer.

Every function returns (positions (N, 3) float32, normals (N, 3) float32 unit, indices (M, 3)
uint32). Conventions follow SDF: a box is centred with full extents `size`; a cylinder is
centred, its axis along local Z; a sphere is centred; a plane is a finite square
`plane_size` (x, y extents) through the origin, perpendicular to `normal`; a mesh is drawn with
flat (per-face) normals, as STL/DAE models with hard edges look in Gazebo.
"""
import math

import numpy as np

from ode_sim.description.model import ModelError

CYLINDER_SEGMENTS = 32
SPHERE_SLICES = 32
SPHERE_STACKS = 16


def _out(pos, nrm, idx):
    return (np.ascontiguousarray(pos, dtype=np.float32),
            np.ascontiguousarray(nrm, dtype=np.float32),
            np.ascontiguousarray(idx, dtype=np.uint32).reshape(-1, 3))


def box(size):
    sx, sy, sz = (float(v) / 2 for v in size)
    pos, nrm, idx = [], [], []
    # each face: normal axis, sign; corners in CCW order seen from outside
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = np.zeros(3)
            n[axis] = sign
            u = np.zeros(3)
            v = np.zeros(3)
            u[(axis + 1) % 3] = 1.0
            v[(axis + 2) % 3] = 1.0
            if sign < 0:
                u, v = v, u
            half = np.array([sx, sy, sz])
            c = n * half
            base = len(pos)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos.append(c + a * u * half + b * v * half)
                nrm.append(n)
            idx += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return _out(pos, nrm, idx)


def cylinder(radius, length, segments=CYLINDER_SEGMENTS):
    r, h = float(radius), float(length) / 2
    ang = np.linspace(0.0, 2 * math.pi, segments, endpoint=False)
    ca, sa = np.cos(ang), np.sin(ang)
    ring = np.stack([r * ca, r * sa, np.zeros(segments)], axis=1)
    side_n = np.stack([ca, sa, np.zeros(segments)], axis=1)
    pos = [ring + [0, 0, -h], ring + [0, 0, h]]
    nrm = [side_n, side_n]
    idx = []
    for i in range(segments):
        j = (i + 1) % segments
        idx += [(i, j, segments + j), (i, segments + j, segments + i)]
    # caps: centre vertex + own ring (flat normals)
    for sign in (1.0, -1.0):
        base = segments * 2 + (0 if sign > 0 else segments + 1)
        pos.append(np.array([[0.0, 0.0, sign * h]]))
        pos.append(ring + [0, 0, sign * h])
        nrm.append(np.tile([0.0, 0.0, sign], (segments + 1, 1)))
        for i in range(segments):
            j = (i + 1) % segments
            a, b = base + 1 + i, base + 1 + j
            idx.append((base, a, b) if sign > 0 else (base, b, a))
    return _out(np.concatenate(pos), np.concatenate(nrm), idx)


def sphere(radius, slices=SPHERE_SLICES, stacks=SPHERE_STACKS):
    r = float(radius)
    theta = np.linspace(0.0, math.pi, stacks + 1)           # from +Z down to -Z
    phi = np.linspace(0.0, 2 * math.pi, slices + 1)          # seam duplicated
    t, p = np.meshgrid(theta, phi, indexing='ij')
    n = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1).reshape(-1, 3)
    idx = []
    w = slices + 1
    for i in range(stacks):
        for j in range(slices):
            a, b = i * w + j, i * w + j + 1
            c, d = (i + 1) * w + j, (i + 1) * w + j + 1
            if i > 0:
                idx.append((a, c, b))
            if i < stacks - 1:
                idx.append((b, c, d))
    return _out(n * r, n, idx)


def plane(normal, plane_size):
    n = np.asarray(normal, dtype=float)
    nn = np.linalg.norm(n)
    if not np.isfinite(nn) or nn == 0:
        raise ValueError('plane normal %s is not a direction' % list(normal))
    n = n / nn
    # in-plane axes: for the default normal +Z these are the shape's X and Y
    ref = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = ref - n * ref.dot(n)
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    hx, hy = float(plane_size[0]) / 2, float(plane_size[1]) / 2
    pos = [a * hx * u + b * hy * v for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    return _out(pos, [n] * 4, [(0, 1, 2), (0, 2, 3)])


def mesh(vertices, faces):
    """Flat-shaded triangles: every face gets its own three vertices and its face normal."""
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise ValueError('mesh needs vertices (N, 3) and faces (M, 3), got %s and %s'
                         % (v.shape, f.shape))
    if len(f) and (f.min() < 0 or f.max() >= len(v)):
        raise ValueError('mesh face index out of range (0..%d)' % (len(v) - 1))
    tri = v[f]                                             # (M, 3, 3)
    fn = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    ln = np.linalg.norm(fn, axis=1, keepdims=True)
    fn = np.where(ln > 0, fn / np.where(ln > 0, ln, 1), [0.0, 0.0, 1.0])
    pos = tri.reshape(-1, 3)
    nrm = np.repeat(fn, 3, axis=0)
    return _out(pos, nrm, np.arange(len(pos)).reshape(-1, 3))


def tessellate(geometry, where=''):
    """Mesh of a model.Geometry; bad or missing data raises ModelError naming `where`."""
    g = geometry
    what = '%s: %s geometry' % (where or 'geometry', g.kind)
    try:
        if g.kind == 'box':
            if len(g.size) != 3 or min(g.size) <= 0:
                raise ValueError('box size must be 3 positive numbers, got %s' % list(g.size))
            return box(g.size)
        if g.kind == 'cylinder':
            if g.radius <= 0 or g.length <= 0:
                raise ValueError('cylinder radius and length must be positive, got %g, %g'
                                 % (g.radius, g.length))
            return cylinder(g.radius, g.length)
        if g.kind == 'sphere':
            if g.radius <= 0:
                raise ValueError('sphere radius must be positive, got %g' % g.radius)
            return sphere(g.radius)
        if g.kind == 'plane':
            if len(g.plane_size) != 2 or min(g.plane_size) <= 0:
                raise ValueError('plane size must be 2 positive numbers, got %s'
                                 % list(g.plane_size))
            return plane(g.normal, g.plane_size)
        if g.kind == 'mesh':
            if g.vertices is None or g.faces is None:
                raise ValueError('mesh %r has no vertices/faces loaded'
                                 % (g.filename or g.uri or '?'))
            return mesh(g.vertices, g.faces)
    except ValueError as e:
        raise ModelError('%s: %s' % (what, e)) from None
    raise ModelError('%s: unknown geometry kind %r (box, cylinder, sphere, plane, mesh)'
                     % (where or 'geometry', g.kind))


def uv_of(geometry, pos, nrm):
    """Texture coordinates (N, 2) float32 of a primitive's tessellated vertices, as a texture
    looks on Gazebo's shapes: box sides upright (u to the right seen from outside, v up), top
    and bottom u along x, v along y; cylinders and spheres wrapped around Z (u the azimuth, v
    the height or latitude), cylinder caps and planes projected. A mesh without its own texture
    coordinates (STL) gets (0, 0)."""
    g = geometry
    p = np.asarray(pos, dtype=float)
    n = np.asarray(nrm, dtype=float)
    uv = np.zeros((len(p), 2))
    if g.kind == 'box':
        sx, sy, sz = (float(v) for v in g.size)
        side = np.abs(n[:, 2]) < 0.5
        # seen from outside (looking along -n, Z up) the right is (-n) x Z = (-n_y, n_x, 0)
        right = np.stack([-n[:, 1], n[:, 0], np.zeros(len(n))], axis=1)
        half = np.array([sx, sy, sz]) / 2
        u_side = (np.einsum('ij,ij->i', p, right) + np.abs(right) @ half) / \
            np.maximum(2 * (np.abs(right) @ half), 1e-12)
        uv[:, 0] = np.where(side, u_side, (p[:, 0] + sx / 2) / sx)
        uv[:, 1] = np.where(side, (p[:, 2] + sz / 2) / sz, (p[:, 1] + sy / 2) / sy)
    elif g.kind in ('cylinder', 'sphere'):
        az = np.arctan2(p[:, 1], p[:, 0]) / (2 * math.pi) + 0.5
        if g.kind == 'sphere':
            uv[:, 0] = az
            uv[:, 1] = 0.5 + np.arcsin(np.clip(p[:, 2] / g.radius, -1, 1)) / math.pi
        else:
            cap = np.abs(n[:, 2]) > 0.5
            uv[:, 0] = np.where(cap, p[:, 0] / (2 * g.radius) + 0.5, az)
            uv[:, 1] = np.where(cap, p[:, 1] / (2 * g.radius) + 0.5, p[:, 2] / g.length + 0.5)
    elif g.kind == 'plane':
        # plane(): corners (-1,-1) (1,-1) (1,1) (-1,1) of its in-plane axes, in that order
        corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        uv[:] = np.tile(corners, (len(p) // 4 + 1, 1))[:len(p)]
    return np.ascontiguousarray(uv, dtype=np.float32)
