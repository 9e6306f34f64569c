"""Map: likelihood field against brute force, coordinates, ray casting."""
import numpy as np
import pytest

from amcl.map import Map
from amcl_synthetic import room_map


def test_likelihood_field_matches_brute_force():
    rng = np.random.default_rng(1)
    cells = np.where(rng.random((30, 40)) < 0.05, 1, -1).astype(np.int8)
    m = Map(cells, 0.1, -1.0, 2.0)
    d = m.update_cspace(0.8)
    oj, oi = np.nonzero(cells == 1)
    for j in range(30):
        for i in range(40):
            brute = min(np.min(np.hypot(oi - i, oj - j)) * 0.1, 0.8)
            assert d[j, i] == pytest.approx(brute, abs=1e-9)


def test_world_map_round_trip_and_outside():
    m = room_map()
    m.update_cspace(2.0)
    i, j = m.world_to_map(np.array([0.025, 5.99]), np.array([0.025, 3.99]))
    assert list(i) == [0, 119] and list(j) == [0, 79]
    x, y = m.map_to_world(i, j)
    assert x[0] == pytest.approx(0.025) and y[1] == pytest.approx(3.975)
    d, inside = m.occ_dist_at(np.array([-1.0, 0.025]), np.array([1.0, 0.025]))
    assert list(inside) == [False, True] and d[0] == 2.0 and d[1] == 0.0


def test_calc_range_hits_walls():
    m = room_map()
    r = m.calc_range(3.0, 2.0, np.array([0.0, np.pi / 2, np.pi, -np.pi / 2]), 12.0)
    # x 3.0 -> the block at x 4.5 (y 1.5..3); up: wall row at 3.95; left: wall column 0..0.05
    assert r == pytest.approx([1.5, 1.95, 2.95, 1.95], abs=0.05)


def test_bad_map_rejected():
    with pytest.raises(ValueError, match='resolution'):
        Map(np.zeros((3, 3)), 0.0)
    with pytest.raises(ValueError, match='non-empty'):
        Map(np.zeros((0, 3)), 0.05)
