"""explore_lite's frontier core on small grids (no master)."""
import numpy as np
import pytest

from explore_lite import frontiers as F


def room(unknown_from_col=None):
    """A 20x30 room (0.1 m cells): walls around, free inside; columns >= unknown_from_col unknown."""
    c = np.full((20, 30), F.FREE_SPACE, dtype=np.uint8)
    c[0, :] = c[-1, :] = c[:, 0] = c[:, -1] = F.LETHAL_OBSTACLE
    if unknown_from_col is not None:
        c[1:-1, unknown_from_col:-1] = F.NO_INFORMATION
    return F.Grid(c, 0.1, (0.0, 0.0))


def test_occupancy_translation_table():
    out = F.occupancy_to_costmap(np.array([-1, 0, 1, 50, 98, 99, 100]))
    assert out.tolist()[0:2] == [255, 0]
    assert out[2] == 1 and out[4] == 252 and out[5] == 253 and out[6] == 254
    assert 1 < out[3] < 252


def test_known_room_has_no_frontier():
    assert F.search(room(), (1.0, 1.0)) == []


def test_frontier_at_the_edge_of_the_unknown():
    g = room(unknown_from_col=20)
    found = F.search(g, (0.5, 1.0), min_frontier_size=0.5)
    assert len(found) == 1
    f = found[0]
    assert f.size == 18                               # the column of unknown cells next to free ones
    assert f.centroid[0] == pytest.approx(2.05)       # cells of column 20
    assert f.min_distance == pytest.approx(np.hypot(2.05 - 0.5, 0.95 - 1.0), abs=0.01)
    assert f.cost == pytest.approx(1e-3 * f.min_distance - 1.0 * 18 * 0.1)


def test_small_frontiers_are_dropped_and_cost_orders():
    g = room()
    g.costs[5, 10] = F.NO_INFORMATION          # a single unknown cell: 0.1 m < min size
    g.costs[1:-1, 25:-1] = F.NO_INFORMATION    # a long frontier far away
    found = F.search(g, (0.5, 0.5), min_frontier_size=0.5)
    assert len(found) == 1 and found[0].centroid[0] == pytest.approx(2.55)
    both = F.search(g, (0.5, 0.5), min_frontier_size=0.0)
    assert len(both) == 2 and both[0].size > both[1].size   # gain beats distance by default
    near_first = F.search(g, (0.5, 0.5), potential_scale=100.0, min_frontier_size=0.0)
    assert near_first[0].size == 1


def test_unreachable_frontier_behind_a_wall_is_ignored():
    g = room(unknown_from_col=20)
    g.costs[1:-1, 10] = F.LETHAL_OBSTACLE      # a wall splits the room
    assert F.search(g, (0.5, 1.0)) == []
    assert len(F.search(g, (1.5, 1.0))) == 1    # from the other side it is reachable


def test_robot_on_an_obstacle_starts_from_the_nearest_free_cell():
    g = room(unknown_from_col=20)
    found = F.search(g, (0.05, 1.0))           # in the wall
    assert len(found) == 1


def test_robot_outside_the_map_is_an_error():
    with pytest.raises(ValueError, match='outside the costmap'):
        F.search(room(), (-5.0, 0.0))


def test_blacklist_and_progress():
    b = F.Blacklist(0.5)
    b.add((1.0, 1.0))
    assert (1.2, 0.8) in b and (1.6, 1.0) not in b
    p = F.Progress(30.0)
    assert not p.update((1, 1), 5.0, 0.0)
    assert not p.update((1, 1), 4.0, 20.0)       # nearer: progress
    assert not p.update((1, 1), 4.0, 45.0)       # 25 s without progress
    assert p.update((1, 1), 4.5, 51.0)           # 31 s: given up
    assert not p.update((2, 2), 4.5, 52.0)       # a new goal starts again
