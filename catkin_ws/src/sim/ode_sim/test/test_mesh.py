"""ode_sim.description.mesh: STL (ASCII, binary) and OBJ loading, de-duplication, scale, cache, errors."""
import os
import struct

import numpy as np
import pytest

from ode_sim.description.mesh import load_stl
from ode_sim.description.model import ModelError

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(HERE, 'fixtures', 'loaders', 'meshes')


def _write_binary_stl(path, tris, header=b'binary test mesh'):
    with open(path, 'wb') as f:
        f.write(header.ljust(80, b' '))
        f.write(struct.pack('<I', len(tris)))
        for t in tris:
            f.write(struct.pack('<3f', 0, 0, 0))
            for p in t:
                f.write(struct.pack('<3f', *p))
            f.write(b'\0\0')


def test_ascii_cube_deduplicated():
    v, f = load_stl(os.path.join(MESHES, 'cube_ascii.stl'))
    assert v.shape == (8, 3) and v.dtype == np.float64
    assert f.shape == (12, 3) and f.dtype == np.int32
    assert np.allclose(np.abs(v), 1.0)
    # every face uses valid, distinct corners
    assert f.min() >= 0 and f.max() < 8
    assert all(len(set(row)) == 3 for row in f.tolist())


def test_scale_applied_and_cached_per_scale():
    p = os.path.join(MESHES, 'cube_ascii.stl')
    v1, _ = load_stl(p, (0.5, 2.0, 1.0))
    assert np.allclose(v1.max(axis=0), [0.5, 2.0, 1.0])
    v2, _ = load_stl(p, (0.5, 2.0, 1.0))
    assert v2 is v1                       # cached
    v3, _ = load_stl(p)
    assert v3 is not v1 and np.allclose(v3.max(axis=0), [1, 1, 1])
    with pytest.raises(ValueError):
        v1[0, 0] = 5.0                    # shared arrays are read-only


def test_binary_stl_even_with_solid_header(tmp_path):
    tris = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((1, 0, 0), (1, 1, 0), (0, 1, 0))]
    p = str(tmp_path / 'quad.stl')
    _write_binary_stl(p, tris, header=b'solid exported by a CAD tool')
    v, f = load_stl(p)
    assert v.shape == (4, 3) and f.shape == (2, 3)
    assert np.allclose(sorted(map(tuple, v.tolist())), [(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0)])


def test_repo_mesh_loads():
    p = os.path.join(HERE, '..', '..', '..', 'course', 'my_robot_model', 'models',
                     'base_frame.stl')
    v, f = load_stl(p)
    assert len(v) > 8 and len(f) > 12
    assert np.all(np.isfinite(v))


def test_obj_quad_is_triangulated():
    v, f = load_stl(os.path.join(MESHES, 'square.obj'))
    assert v.shape == (4, 3) and f.shape == (2, 3)


@pytest.mark.parametrize('name, expected', [
    ('empty.stl', 'cannot read'),
    ('garbage.stl', 'cannot read'),
    ('thing.dae', 'cannot read: Collada: File came out empty'),
    ('missing.stl', 'cannot read'),
])
def test_bad_meshes_one_line(name, expected):
    p = os.path.join(MESHES, name)
    with pytest.raises(ModelError) as e:
        load_stl(p)
    msg = str(e.value)
    assert msg.startswith('mesh %s: ' % p), msg
    assert expected in msg and '\n' not in msg


def test_truncated_binary(tmp_path):
    p = str(tmp_path / 'cut.stl')
    _write_binary_stl(p, [((0, 0, 0), (1, 0, 0), (0, 1, 0))] * 3)
    data = open(p, 'rb').read()
    open(p, 'wb').write(data[:-60])
    with pytest.raises(ModelError, match='cannot read: not an STL file'):
        load_stl(p)
