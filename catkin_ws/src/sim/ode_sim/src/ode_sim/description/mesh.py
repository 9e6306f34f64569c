"""Triangle meshes for collision (ODE trimesh), the lidar's rays and the camera.

STL (ASCII and binary) is read here: a flat array of triangles, exact and fast, so the physics
of existing worlds does not change. COLLADA (.dae), Wavefront OBJ with its MTL and every other
format assimp reads go through Debian's assimp in the compiled core (`_core.import_mesh`, C++
on libassimp, the library RViz reads the same files with). A COLLADA file's <unit> is applied
by assimp; its <up_axis> is turned to Z up as Gazebo does (Y_UP: +90 deg about X, X_UP: -90 deg
about Y). Every mesh instance of every node comes with its node's accumulated transform, so a
file's several geometries land where the file puts them.

`load_mesh(path, scale, submesh, center)` gives a LoadedMesh: the collision triangles (vertices
de-duplicated and scaled, float64, read-only; faces int32), and for assimp formats the render
parts (one per mesh instance: positions, normals, texture coordinates, the file's material).
Results are cached by (path, modification time, scale, submesh, center): a mesh used by many
models is read once and shares one ODE trimesh and one BVH.
"""
import os
import re
import struct
import urllib.parse
import warnings
from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from ode_sim.description.model import Material as MeshMaterial, ModelError

_CACHE = {}       # (path, mtime, scale, submesh, center) -> LoadedMesh
_SCENES = {}      # (path, mtime) -> (parts, materials, warnings) as the file has them

# COLLADA <up_axis> -> rotation to Z up (Gazebo's ColladaLoader)
_UP = {'Y': np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]),
       'X': np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])}


@dataclass
class MeshPart:
    """One mesh instance of a file, for drawing."""
    name: str
    node: str
    positions: np.ndarray           # (N, 3) float32, scaled
    normals: np.ndarray             # (N, 3) float32 unit
    uvs: Optional[np.ndarray]       # (N, 2) float32 or None
    faces: np.ndarray               # (M, 3) uint32, counter-clockwise seen from outside
    material: Optional[MeshMaterial] = None


@dataclass
class LoadedMesh:
    vertices: np.ndarray            # (N, 3) float64, de-duplicated, scaled (collision, rays)
    faces: np.ndarray               # (M, 3) int32
    parts: List[MeshPart] = field(default_factory=list)   # empty: draw vertices/faces flat
    warnings: List[str] = field(default_factory=list)


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


def _core():
    try:
        from ode_sim.engine import _core as core
    except ImportError as e:
        raise ModelError('ode_sim: the compiled engine core ode_sim.engine._core is not built '
                         '(%s): run scripts/build.sh' % e) from None
    return core


def _up_axis(path):
    """'X', 'Y' or 'Z': the <up_axis> of a COLLADA file's <asset> (Z for other formats)."""
    if not path.lower().endswith('.dae'):
        return 'Z'
    try:
        with open(path, 'rb') as f:
            head = f.read(65536).decode('utf-8', errors='replace')
    except OSError:
        return 'Z'
    m = re.search(r'<up_axis>\s*([XYZ])_UP\s*</up_axis>', head)
    return m.group(1) if m else 'Y'          # COLLADA's default is Y_UP


def _find_texture(path, tex):
    """(absolute path of a texture named in mesh file `path`, places searched)."""
    t = tex.strip()
    if t.startswith('file://'):
        t = t[len('file://'):]
    t = urllib.parse.unquote(t).replace('\\', '/')
    here = os.path.dirname(path)
    base = os.path.basename(t)
    model_dir = os.path.dirname(here)
    cands = [t] if os.path.isabs(t) else [os.path.join(here, t)]
    cands += [os.path.join(here, base),
              os.path.join(model_dir, 'materials', 'textures', base),
              os.path.join(model_dir, 'textures', base)]
    for c in cands:
        if os.path.isfile(c):
            return os.path.abspath(c), cands
    return None, cands


def _rgba(v, default):
    if v is None:
        return default
    return tuple(float(x) for x in v)


def _scene(path, mtime):
    """The file's parts (rotated to Z up, unscaled) and materials, read once per version."""
    key = (path, mtime)
    hit = _SCENES.get(key)
    if hit is not None:
        return hit
    try:
        meshes, mats = _core().import_mesh(path)
    except RuntimeError as e:
        raise _err(path, 'cannot read: %s' % (str(e).strip() or 'assimp failed')) from None
    notes = []
    materials = []
    for i, m in enumerate(mats):
        name = m['name'] or 'material %d' % i
        diffuse = _rgba(m['diffuse'], (0.7, 0.7, 0.7, 1.0))
        opacity = float(m['opacity'])
        if not 0.0 <= opacity <= 1.0:
            opacity = 1.0
        mat = MeshMaterial(name=name, diffuse=diffuse,
                           ambient=_rgba(m['ambient'], None),
                           emissive=_rgba(m['emissive'], (0, 0, 0, 1))[:3],
                           specular=_rgba(m['specular'], (0, 0, 0, 1))[:3],
                           opacity=opacity * diffuse[3], source=path)
        tex = m['texture']
        if tex:
            if tex.startswith('*'):
                notes.append('mesh %s: material %r: embedded texture %s is not supported; '
                             'drawn in its plain colour' % (path, name, tex))
            else:
                found, searched = _find_texture(path, tex)
                if found is None:
                    notes.append('mesh %s: material %r: texture %r not found (searched: %s); '
                                 'drawn in its plain colour' % (path, name, tex,
                                                                ', '.join(searched)))
                else:
                    mat.texture = found
        materials.append(mat)
    R = _UP.get(_up_axis(path))
    parts = []
    for node, name, mi, pos, nrm, uv, faces in meshes:
        if R is not None:
            pos = pos @ R.T
            nrm = (nrm.astype(np.float64) @ R.T).astype(np.float32)
        if not np.all(np.isfinite(pos)):
            raise _err(path, 'cannot read: mesh %r has non-finite coordinates' % (name or node))
        parts.append((node, name, materials[mi] if 0 <= mi < len(materials) else None,
                      pos, nrm, uv, faces))
    if not parts:
        raise _err(path, 'cannot read: the file has no triangles (no mesh, or only points and '
                         'lines)')
    hit = (parts, notes)
    _SCENES[key] = hit
    return hit


def _collision_arrays(path, tris):
    """De-duplicated (vertices, faces) of (M, 3, 3) scaled triangle corners."""
    if tris.shape[0] == 0:
        raise _err(path, 'cannot read: the mesh has no triangles')
    if not np.all(np.isfinite(tris)):
        raise _err(path, 'cannot read: the mesh has non-finite coordinates')
    flat = tris.reshape(-1, 3)
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
    return verts, faces


def _names(parts):
    out = []
    for node, name, *_ in parts:
        for n in (node, name):
            if n and n not in out:
                out.append(n)
    return out


def load_mesh(path, scale=(1.0, 1.0, 1.0), submesh=None, center=False):
    """LoadedMesh of mesh file `path` scaled by `scale`; `submesh` (SDF <submesh><name>): only
    the mesh instances whose node or mesh name is that, moved so that their bounding box is
    centred on the origin when `center`. Bad input: ModelError 'mesh PATH: what'."""
    path = os.path.abspath(path)
    scale = tuple(float(s) for s in scale)
    submesh = (submesh or '').strip() or None
    try:
        mtime = os.path.getmtime(path)
    except OSError as e:
        raise _err(path, 'cannot read: %s' % (e.strerror or e))
    key = (path, mtime, scale, submesh, bool(center) and submesh is not None)
    hit = _CACHE.get(key)
    if hit is not None:
        return hit
    if not all(np.isfinite(scale)) or any(s == 0 for s in scale):
        raise _err(path, '<scale> must be finite and non-zero, got %s' % (scale,))
    s = np.array(scale)
    if path.lower().endswith('.stl'):
        try:
            with open(path, 'rb') as f:
                data = f.read()
        except OSError as e:
            raise _err(path, 'cannot read: %s' % (e.strerror or e))
        if submesh is not None:
            raise _err(path, '<submesh> %r: an STL file has a single mesh' % submesh)
        tris = _read_stl_triangles(path, data)
        verts, faces = _collision_arrays(path, tris * s)
        out = LoadedMesh(verts, faces)
        _CACHE[key] = out
        return out
    parts, notes = _scene(path, mtime)
    if submesh is not None:
        chosen = [p for p in parts if submesh in (p[0], p[1])]
        if not chosen:
            raise _err(path, '<submesh> %r not found (the file has: %s)'
                       % (submesh, ', '.join(_names(parts)) or 'no named meshes'))
        parts = chosen
    shift = np.zeros(3)
    if key[4]:
        allpos = np.concatenate([p[3] for p in parts])
        shift = -(allpos.min(axis=0) + allpos.max(axis=0)) / 2
    flip = np.prod(np.sign(s)) < 0
    render, tris = [], []
    for node, name, mat, pos, nrm, uv, faces in parts:
        p = (pos + shift) * s
        n = nrm / s
        ln = np.linalg.norm(n, axis=1, keepdims=True)
        n = np.where(ln > 0, n / np.where(ln > 0, ln, 1), 0.0)
        f = faces[:, ::-1] if flip else faces
        tris.append(p[f])
        render.append(MeshPart(name=name, node=node, positions=p.astype(np.float32),
                               normals=n.astype(np.float32), uvs=uv,
                               faces=np.ascontiguousarray(f, dtype=np.uint32), material=mat))
    verts, faces = _collision_arrays(path, np.concatenate(tris))
    out = LoadedMesh(verts, faces, render, list(notes))
    _CACHE[key] = out
    return out


def load_stl(path, scale=(1.0, 1.0, 1.0)):
    """(vertices (N, 3) float64, faces (M, 3) int32) of the mesh file, scaled, vertices
    de-duplicated. The arrays are shared (read-only): copy before changing them."""
    m = load_mesh(path, scale)
    return m.vertices, m.faces
