"""Triangle meshes for collision (ODE trimesh) and rendering: STL (ASCII and binary) and,
cheaply, Wavefront OBJ (vertices and faces only). Vertices are de-duplicated and scaled;
results are cached by (path, modification time, scale)."""
import os
import struct
import warnings

import numpy as np

from ode_sim.description.model import ModelError

_CACHE = {}


def _err(path, what):
    return ModelError('mesh %s: %s' % (path, what))


def _read_stl_triangles(path, data):
    """(M, 3, 3) float array of triangle corners."""
    head = data[:256].lstrip()
    binary_size_ok = (len(data) >= 84
                      and len(data) == 84 + 50 * struct.unpack('<I', data[80:84])[0])
    is_ascii = (not binary_size_ok and head[:5].lower() == b'solid'
                and b'facet' in data[:4096])
    if not is_ascii:
        if len(data) < 84:
            raise _err(path, 'cannot read: too short for a binary STL (%d bytes)' % len(data))
        (count,) = struct.unpack('<I', data[80:84])
        if len(data) < 84 + 50 * count:
            raise _err(path, 'cannot read: not an STL file (binary header says %d triangles, '
                             'file has %d bytes)' % (count, len(data)))
        rec = np.dtype([('n', '<f4', (3,)), ('v', '<f4', (3, 3)), ('attr', '<u2')])
        arr = np.frombuffer(data, dtype=rec, count=count, offset=84)
        return arr['v'].astype(np.float64)
    # ASCII: the numbers after each 'vertex' keyword
    try:
        text = data.decode('ascii', errors='replace')
    except Exception as e:  # pragma: no cover
        raise _err(path, 'cannot read: %s' % e)
    tokens = text.split()
    verts = []
    for i, tok in enumerate(tokens):
        if tok == 'vertex':
            try:
                verts.append((float(tokens[i + 1]), float(tokens[i + 2]), float(tokens[i + 3])))
            except (IndexError, ValueError):
                raise _err(path, 'cannot read: bad vertex line in ASCII STL')
    if len(verts) % 3:
        raise _err(path, 'cannot read: ASCII STL vertex count %d is not a multiple of 3'
                   % len(verts))
    return np.array(verts, dtype=np.float64).reshape(-1, 3, 3)


def _read_obj(path, data):
    verts, faces = [], []
    for line in data.decode('utf-8', errors='replace').splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == 'v':
            try:
                verts.append([float(x) for x in parts[1:4]])
            except ValueError:
                raise _err(path, 'cannot read: bad vertex line %r' % line)
        elif parts[0] == 'f':
            idx = []
            for p in parts[1:]:
                try:
                    k = int(p.split('/')[0])
                except ValueError:
                    raise _err(path, 'cannot read: bad face line %r' % line)
                idx.append(k - 1 if k > 0 else len(verts) + k)
            for j in range(1, len(idx) - 1):       # fan triangulation
                faces.append((idx[0], idx[j], idx[j + 1]))
    if not verts or not faces:
        raise _err(path, 'cannot read: no vertices/faces in OBJ file')
    v = np.array(verts, dtype=np.float64)
    f = np.array(faces, dtype=np.int64)
    if f.min() < 0 or f.max() >= len(v):
        raise _err(path, 'cannot read: OBJ face index out of range')
    return v[f]


def _triangles(path):
    ext = os.path.splitext(path)[1].lower()
    if ext not in ('.stl', '.obj'):
        raise _err(path, 'only STL meshes are supported (and OBJ); convert %s to STL'
                   % (ext or 'this file'))
    try:
        with open(path, 'rb') as f:
            data = f.read()
    except OSError as e:
        raise _err(path, 'cannot read: %s' % (e.strerror or e))
    if ext == '.obj':
        return _read_obj(path, data)
    return _read_stl_triangles(path, data)


def load_stl(path, scale=(1.0, 1.0, 1.0)):
    """(vertices (N, 3) float64, faces (M, 3) int32) of the mesh file, scaled, vertices
    de-duplicated. The arrays are shared (read-only): copy before changing them."""
    path = os.path.abspath(path)
    scale = tuple(float(s) for s in scale)
    try:
        mtime = os.path.getmtime(path)
    except OSError as e:
        raise _err(path, 'cannot read: %s' % (e.strerror or e))
    key = (path, mtime, scale)
    hit = _CACHE.get(key)
    if hit is not None:
        return hit
    tris = _triangles(path)
    if tris.shape[0] == 0:
        raise _err(path, 'cannot read: the mesh has no triangles')
    if not np.all(np.isfinite(tris)):
        raise _err(path, 'cannot read: the mesh has non-finite coordinates')
    flat = tris.reshape(-1, 3) * np.array(scale)
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        verts, inverse = np.unique(flat, axis=0, return_inverse=True)
    faces = inverse.reshape(-1, 3).astype(np.int32)
    # drop triangles that collapsed to a line/point (duplicate corners)
    ok = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    faces = np.ascontiguousarray(faces[ok])
    if faces.shape[0] == 0:
        raise _err(path, 'cannot read: all triangles are degenerate')
    verts = np.ascontiguousarray(verts, dtype=np.float64)
    verts.flags.writeable = False
    faces.flags.writeable = False
    _CACHE[key] = (verts, faces)
    return verts, faces


load_mesh = load_stl
