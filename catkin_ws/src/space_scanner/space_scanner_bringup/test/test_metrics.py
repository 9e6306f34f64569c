"""The main demo's figures on synthetic data (no master)."""
import numpy as np
import pytest

from space_scanner_bringup import metrics as M


def room(shift_cells=0, noise=()):
    g = np.full((40, 60), -1, dtype=np.int8)
    g[5:35, 5:55] = 0
    g[5, 5:55] = g[34, 5:55] = g[5:35, 5] = g[5:35, 54] = 100
    g = np.roll(g, shift_cells, axis=1)
    for r, c in noise:
        g[r, c] = 100
    return g


def test_ate_interpolates_ground_truth():
    truth = [(0.0, 0.0, 0.0), (10.0, 10.0, 0.0)]
    est = [(1.0, 1.0, 0.1), (5.0, 5.0, -0.1), (9.0, 9.0, 0.1), (20.0, 0, 0)]   # last: outside
    rms, mx = M.ate(est, truth)
    assert rms == pytest.approx(0.1) and mx == pytest.approx(0.1)
    with pytest.raises(ValueError):
        M.ate([], truth)


def test_identical_maps_are_perfect():
    q = M.map_quality((room(), 0.05, (0, 0)), (room(), 0.05, (0, 0)))
    assert q['walls_found'] == 1.0 and q['false_occupied'] == 0.0
    assert q['known_area'] == pytest.approx(28 * 48 * 0.0025)


def test_one_cell_shift_is_tolerated_two_are_not():
    truth = (room(), 0.05, (0, 0))
    assert M.map_quality((room(1), 0.05, (0, 0)), truth)['walls_found'] > 0.99
    q = M.map_quality((room(3), 0.05, (0, 0)), truth)
    assert q['walls_found'] < 0.8 and q['false_occupied'] > 0.2


def test_false_occupied_counts_phantom_walls():
    q = M.map_quality((room(noise=[(20, 20), (21, 30)]), 0.05, (0, 0)), (room(), 0.05, (0, 0)))
    total = (room() == 100).sum() + 2
    assert q['false_occupied'] == pytest.approx(2 / total)


def test_origin_offsets_are_world_coordinates():
    # the same room in a map whose origin is one metre off: compare by world position
    shifted = np.full((60, 80), -1, dtype=np.int8)
    shifted[20:60, 20:80] = room()
    q = M.map_quality((shifted, 0.05, (-1.0, -1.0)), (room(), 0.05, (0, 0)))
    assert q['walls_found'] == 1.0 and q['false_occupied'] == 0.0
