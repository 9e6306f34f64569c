"""The committed models/base_frame.stl is what scripts/make_base_frame_stl.py writes, and it is
a closed, outward-facing solid with the body's dimensions."""
import collections
import os
import subprocess
import warnings

import numpy as np
import pytest

from my_robot_model import base_frame

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STL = os.path.join(PKG, 'models', 'base_frame.stl')


def test_script_reproduces_the_committed_file(tmp_path):
    out = tmp_path / 'base_frame.stl'
    r = subprocess.run([os.path.join(PKG, 'scripts', 'make_base_frame_stl.py'), str(out)],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    with open(STL, 'rb') as f:
        committed = f.read()
    assert out.read_bytes() == committed
    assert len(committed) < 10000


def test_mesh_is_closed_outward_and_sized():
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        from stl import mesh
        m = mesh.Mesh.from_file(STL)
    # every directed edge once, and its reverse once: a closed, consistently wound surface
    edges = collections.Counter()
    for tri in m.vectors.round(6):
        pts = [tuple(p) for p in tri]
        for a, b in zip(pts, pts[1:] + pts[:1]):
            edges[(a, b)] += 1
    assert all(n == 1 for n in edges.values())
    assert all((b, a) in edges for a, b in edges)
    volume = m.get_mass_properties()[0]
    L, W, H, c, w, fl = (base_frame.LENGTH, base_frame.WIDTH, base_frame.HEIGHT, base_frame.CHAMFER,
                         base_frame.WALL, base_frame.FLOOR)
    outer = base_frame.polygon_area(base_frame.octagon(L, W, c))
    inner = base_frame.polygon_area(base_frame.octagon(L - 2 * w, W - 2 * w, c - w * (2 - np.sqrt(2))))
    assert outer == pytest.approx(L * W - 2 * c * c)
    assert volume == pytest.approx(outer * H - inner * (H - fl), rel=1e-5)   # > 0: normals point out
    assert m.min_ == pytest.approx([-L / 2, -W / 2, -H / 2]) and m.max_ == pytest.approx([L / 2, W / 2, H / 2])


def test_bad_dimensions_are_one_line_errors(tmp_path):
    r = subprocess.run([os.path.join(PKG, 'scripts', 'make_base_frame_stl.py'), str(tmp_path / 'x.stl'),
                        '--wall', '0.2'], capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and 'leave no pocket' in r.stderr and 'Traceback' not in r.stderr
    with pytest.raises(ValueError, match='height must be > 0'):
        base_frame.tray_triangles(height=0)
