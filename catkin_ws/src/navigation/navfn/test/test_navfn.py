"""navfn core without a master: costs, potential, gradient path."""
import math

import numpy as np

from navfn.navfn import (COST_NEUTRAL, COST_OBS, POT_HIGH, NavFn, navfn_costs, propagate)


def path_length(p):
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(p[:-1], p[1:]))


def test_costs_translation():
    c = np.array([[0, 100, 252, 253, 254, 255]] * 3, dtype=np.uint8)
    c = np.pad(c, 1)
    out = navfn_costs(c, allow_unknown=True)
    row = out[2, 1:-1]
    assert list(row[:3]) == [COST_NEUTRAL, COST_NEUTRAL + 0.8 * 100, COST_NEUTRAL + 0.8 * 252]
    assert row[3] == COST_OBS and row[4] == COST_OBS       # inscribed and lethal: obstacles
    assert row[5] == COST_OBS - 1                            # unknown allowed
    assert navfn_costs(c, allow_unknown=False)[2, 6] == COST_OBS
    assert (out[0] == COST_OBS).all() and (out[:, 0] == COST_OBS).all()   # borders


def test_potential_grows_with_distance_on_free_grid():
    costs = navfn_costs(np.zeros((21, 21), dtype=np.uint8))
    pot = propagate(costs, (10, 10))
    assert pot[10, 10] == 0
    assert pot[10, 11] == COST_NEUTRAL
    # along an axis: one neutral cost per cell; diagonals less than the Manhattan sum
    assert pot[10, 15] == COST_NEUTRAL * 5
    assert pot[15, 15] < COST_NEUTRAL * 10
    assert pot[15, 15] > COST_NEUTRAL * 5 * math.sqrt(2) * 0.95
    assert (pot[0] == POT_HIGH).all()       # borders are obstacles


def test_path_straight_and_around_a_wall():
    grid = np.zeros((40, 60), dtype=np.uint8)
    nf = NavFn()
    p = nf.plan(grid, (5, 20), (50, 20))
    assert p[0] == (5, 20) and p[-1] == (50.0, 20.0)
    assert path_length(p) < 45 * 1.02
    grid[5:35, 30] = 254                     # a wall with gaps at both ends
    p = nf.plan(grid, (5, 20), (50, 20))
    cells = {(int(round(x)), int(round(y))) for x, y in p}
    assert not any(grid[y, x] == 254 for x, y in cells)
    assert path_length(p) > 45
    shortest = 2 * math.hypot(25, 16)       # around an end of the wall
    assert path_length(p) < shortest * 1.1


def test_no_path_to_an_enclosed_goal_and_tolerance():
    grid = np.zeros((30, 30), dtype=np.uint8)
    grid[10:21, 10] = grid[10:21, 20] = 254
    grid[10, 10:21] = grid[20, 10:21] = 254
    nf = NavFn()
    assert nf.plan(grid, (3, 3), (15, 15)) == []
    grid2 = np.zeros((30, 30), dtype=np.uint8)
    grid2[15, 15] = 254                      # the goal itself is lethal
    assert nf.plan(grid2, (3, 3), (15, 15)) == []
    p = nf.plan(grid2, (3, 3), (15, 15), tolerance_cells=1.5)
    assert p and math.hypot(p[-1][0] - 15, p[-1][1] - 15) <= 1.5


def test_astar_gives_the_same_length():
    grid = np.zeros((40, 60), dtype=np.uint8)
    grid[5:35, 30] = 254
    d = path_length(NavFn().plan(grid, (5, 20), (50, 20)))
    a = path_length(NavFn(astar=True).plan(grid, (5, 20), (50, 20)))
    assert abs(a - d) / d < 0.05


def test_native_propagation_matches_the_python_one():
    rng = np.random.default_rng(3)
    grid = (rng.random((30, 40)) < 0.15).astype(np.uint8) * 254
    grid[2, 2] = grid[25, 35] = 0
    costs = navfn_costs(grid)
    for astar in (False, True):
        a = propagate(costs, (2, 2), (35, 25), astar, native=True)
        b = propagate(costs, (2, 2), (35, 25), astar, native=False)
        assert a[25, 35] == b[25, 35]
    full_a = propagate(costs, (2, 2), None, native=True)
    full_b = propagate(costs, (2, 2), None, native=False)
    assert np.array_equal(full_a, full_b)
