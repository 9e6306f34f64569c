"""Trajectory rollout core without a master: map grids, simulation, scoring, choice."""

import numpy as np
import pytest

from base_local_planner.trajectory_planner import (LocalGrid, TrajectoryParams,
                                                   TrajectoryPlanner, plan_cells, wavefront)

FOOTPRINT = [(-0.09, -0.13), (-0.09, 0.13), (0.09, 0.13), (0.09, -0.13)]


def free_grid(n=60, res=0.05):
    return LocalGrid(np.zeros((n, n), dtype=np.uint8), res, 0.0, 0.0)


def test_wavefront_goes_around_obstacles():
    g = free_grid(10, 1.0)
    g.data[0:8, 5] = 254
    d, impossible = wavefront(g, [(0, 0)])
    assert d[0, 4] == 4
    assert d[0, 6] == 4 + 8 + 8 + 2     # up, over the wall's end, down
    assert d[0, 5] == impossible         # the obstacle itself
    assert d[9, 9] == 18


def test_plan_cells_dense():
    g = free_grid(20, 0.1)
    cells = plan_cells(g, [(0.05, 0.05), (1.05, 0.05)])
    assert cells[0] == (0, 0) and cells[-1] == (10, 0) and len(cells) == 11


def test_simulation_respects_acceleration_and_kinematics():
    p = TrajectoryParams(sim_time=1.0, acc_lim_x=1.0, acc_lim_theta=2.0)
    tp = TrajectoryPlanner(p, FOOTPRINT)
    tp.update_plan(free_grid(), [(0.5, 1.5), (2.9, 1.5)])
    tr = tp.simulate(0.5, 1.5, 0.0, 0.0, 0.0, 0.0, [[0.5, 0.0, 0.0], [0.0, 0.0, 1.0]])
    # v ramps 0 -> 0.5 m/s in 0.5 s, then cruises: 0.125 + 0.25 = 0.375 m in 1 s (minus a step)
    assert tr.x[0, -1] - 0.5 == pytest.approx(0.375, abs=0.03)
    assert tr.y[0, -1] == pytest.approx(1.5)
    assert tr.th[1, -1] == pytest.approx(0.75, abs=0.05)   # 0.25 + 0.5 rad
    assert tr.x[1, -1] == pytest.approx(0.5)


def test_cost_terms_and_invalid_trajectories():
    p = TrajectoryParams(sim_time=1.0, pdist_scale=0.6, gdist_scale=0.8, occdist_scale=0.01,
                         dwa=True)
    g = free_grid()
    g.data[:, 40] = 254                    # a wall at x = 2.0 m
    tp = TrajectoryPlanner(p, FOOTPRINT)
    tp.update_plan(g, [(0.5, 1.5), (1.5, 1.5)])
    tr = tp.simulate(0.5, 1.5, 0.0, 0.0, 0.0, 0.0,
                     [[0.5, 0.0, 0.0], [1.6, 0.0, 0.0], [0.0, 0.0, 0.0]])
    # 0.5 m/s for 1 s ends near (1.0, 1.5): on the path, 10 cells from the local goal
    end = tp.grid.cells(np.array([tr.x[0, -1]]), np.array([tr.y[0, -1]]))
    gd = tp.goal_map[end[1][0], end[0][0]]
    assert gd in (10, 11)
    assert tr.cost[0] == pytest.approx(0.8 * gd)
    # 1.6 m/s for 1 s runs into the wall: the footprint check makes it illegal
    assert tp.resolve(tr, 1) is False and tr.cost[1] == -1
    # standing still is valid but far from the goal
    assert tr.cost[2] > tr.cost[0]


def test_find_best_path_drives_towards_the_goal_and_turns_in_place_when_facing_away():
    p = TrajectoryParams(max_vel_x=0.6, min_vel_x=0.35, max_vel_theta=0.85,
                         min_vel_theta=-0.85, min_in_place_vel_theta=0.9, acc_lim_theta=5,
                         acc_lim_x=1, acc_lim_y=1, holonomic_robot=False)
    tp = TrajectoryPlanner(p, FOOTPRINT)
    tp.update_plan(free_grid(), [(0.5, 1.5), (2.5, 1.5)])
    vx, vy, vth, cost, pts = tp.find_best_path(0.5, 1.5, 0.0, 0.0, 0.0, 0.0)
    assert cost >= 0 and vx >= 0.35 and abs(vth) < 0.3
    assert pts[-1, 0] > 0.6
    # facing a wall 0.2 m ahead: no forward arc fits, a rotation in place is chosen
    g = free_grid()
    g.data[:, 17:19] = 254                 # wall at x = 0.85..0.95 m
    tp2 = TrajectoryPlanner(p, FOOTPRINT)
    tp2.update_plan(g, [(0.6, 1.5), (0.6, 2.5)])
    vx, vy, vth, cost, pts = tp2.find_best_path(0.6, 1.5, 0.0, 0.0, 0.0, 0.0)
    assert cost >= 0 and vx == 0.0 and abs(vth) >= 0.9


def test_check_trajectory():
    tp = TrajectoryPlanner(TrajectoryParams(), FOOTPRINT)
    g = free_grid()
    g.data[30, 30] = 254
    tp.update_plan(g, [(0.5, 1.5), (2.5, 1.5)])
    assert tp.check_trajectory(0.5, 0.5, 0.0, 0, 0, 0, 0.0, 0.0, 0.5)
    assert not tp.check_trajectory(1.3, 1.525, 0.0, 0, 0, 0, 0.5, 0.0, 0.0)


def test_native_wavefront_matches_the_python_one():
    rng = np.random.default_rng(5)
    g = LocalGrid((rng.random((40, 50)) < 0.2).astype(np.uint8) * 254, 0.05, 0.0, 0.0)
    seeds = [(3, 3), (10, 30), (45, 38)]
    a, ia = wavefront(g, seeds, native=True)
    b, ib = wavefront(g, seeds, native=False)
    assert ia == ib and np.array_equal(a, b)


def test_footprint_costs_as_costmap_model():
    from base_local_planner import native
    g = free_grid(40, 0.05)
    fp = np.array(FOOTPRINT)
    xs, ys, ths = np.array([[1.0]]), np.array([[1.0]]), np.array([[0.0]])

    def cost():
        return native.footprint_costs(g.data, 0.0, 0.0, 0.05, fp, xs, ys, ths)[0]
    assert cost() == 0.0
    # the right edge x = 1.09 runs through cell column 21: cost 100 there is the pose's cost
    g.data[20, 21] = 100
    assert cost() == 100.0
    g.data[20, 21] = 254                   # lethal on the outline
    assert cost() == -1.0
    g.data[20, 21] = 255                   # unknown on the outline
    assert cost() == -1.0
    g.data[20, 21] = 0
    g.data[20, 20] = 254                   # inside the polygon only: the outline is checked
    assert cost() == 0.0
    xs[0, 0] = 1.95                        # a vertex off the map
    assert cost() == -1.0
    # a circular robot (< 3 points): the centre cell, inscribed illegal too
    g.data[20, 20] = 253
    assert native.footprint_costs(g.data, 0.0, 0.0, 0.05, np.zeros((0, 2)),
                                  np.array([[1.0]]), ys, ths)[0] == -1.0


def test_cells_under_the_robot_do_not_block_the_wavefront():
    g = free_grid(40, 0.05)
    g.data[18:23, 18:23] = 253             # inscribed cells around the robot at (1.0, 1.0)
    tp = TrajectoryPlanner(TrajectoryParams(), FOOTPRINT)
    tp.update_plan(g, [(0.2, 0.2), (0.2, 1.8)])
    assert tp.path_map[20, 20] == 40 * 40          # an obstacle to the wavefront
    tp.update_plan(g, [(0.2, 0.2), (0.2, 1.8)], robot_pose=(1.0, 1.0, 0.0))
    assert tp.path_map[20, 20] == 16               # 16 cells from the path at x = 0.2


def test_plan_cells_are_targets_whatever_their_cost():
    g = free_grid(10, 1.0)
    g.data[5, 5] = 253                     # a plan cell in an inscribed cell
    for native in (True, False):
        d, _ = wavefront(g, [(5, 5)], native=native)
        assert d[5, 5] == 0 and d[5, 6] == 1 and d[0, 0] == 10


DIPLOMA = dict(max_vel_x=0.6, min_vel_x=0.35, max_vel_theta=0.85, min_vel_theta=-0.85,
               min_in_place_vel_theta=0.9, acc_lim_theta=5, acc_lim_x=1, acc_lim_y=1,
               holonomic_robot=False)


def test_rotate_to_goal_speed_clamped_to_max_vel_theta():
    from base_local_planner.trajectory_planner_ros import rotate_to_goal_speed
    p = TrajectoryParams(**DIPLOMA)
    # the diploma's min_in_place_vel_theta 0.9 is above max_vel_theta 0.85: 0.85 (original)
    assert rotate_to_goal_speed(0.3, p) == pytest.approx(0.85)
    assert rotate_to_goal_speed(-0.3, p) == pytest.approx(-0.85)
    q = TrajectoryParams()                                     # 0.4 .. 1.0
    assert rotate_to_goal_speed(0.2, q) == pytest.approx(0.4)
    assert rotate_to_goal_speed(0.7, q) == pytest.approx(0.7)
    assert rotate_to_goal_speed(-2.0, q) == pytest.approx(-1.0)


def test_barred_turns_are_released_after_driving_away_at_the_robots_speed():
    """Two flips bar both turn directions; driving forward at 0.35 m/s (3.5 cm per 0.1 s
    cycle) releases them once 5 cm from where the robot last turned in place (before, the
    release needed 5 cm within one cycle: never at this robot's speeds)."""
    tp = TrajectoryPlanner(TrajectoryParams(**DIPLOMA), FOOTPRINT)
    tp._update_oscillation_flags(1.0, 1.0, 0.0, 0.0, 0.0, -0.9)
    tp._update_oscillation_flags(1.0, 1.0, 0.0, 0.0, 0.0, 0.9)
    tp._update_oscillation_flags(1.0, 1.0, 0.0, 0.0, 0.0, -0.9)
    assert tp.stuck_left and tp.stuck_right
    tp._update_oscillation_flags(1.035, 1.0, 0.0, 0.35, 0.0, 0.3)
    assert tp.stuck_left and tp.stuck_right          # 3.5 cm: still barred
    tp._update_oscillation_flags(1.07, 1.0, 0.0, 0.35, 0.0, 0.3)
    assert not (tp.stuck_left or tp.stuck_right or tp.rotating_left or tp.rotating_right)
    # a new plan starts clean
    tp._update_oscillation_flags(1.07, 1.0, 0.0, 0.0, 0.0, 0.9)
    tp._update_oscillation_flags(1.07, 1.0, 0.0, 0.0, 0.0, -0.9)
    assert tp.stuck_left
    tp.reset_oscillation_flags()
    assert not (tp.stuck_left or tp.stuck_right or tp.rotating_left or tp.rotating_right)


def test_exact_outline_catches_a_wall_corner_between_the_vertex_lines_cells():
    """bench/navigation (a door jamb at (-3.55, 2.05)): the footprint's edge cuts the jamb's
    corner cell, the Bresenham line between the vertices' cells passes beside it
    (CostmapModel: legal) and the robot pushed the jamb for 20 s."""
    from base_local_planner import native
    ox, oy, res = -6.55, -4.55, 0.05
    data = np.zeros((140, 80), dtype=np.uint8)
    data[129:132, 60:] = 254                       # the wall x >= -3.55, 1.90 <= y < 2.05
    pose = np.array([[-3.62892867]]), np.array([[2.13774521]]), np.array([[-2.04744714]])
    fp = np.array(FOOTPRINT)
    assert native.footprint_costs(data, ox, oy, res, fp, *pose)[0] >= 0
    assert native.footprint_costs(data, ox, oy, res, fp, *pose, exact=True)[0] == -1.0
    # the rollout uses the exact outline
    tp = TrajectoryPlanner(TrajectoryParams(**DIPLOMA), FOOTPRINT)
    tp.update_plan(LocalGrid(data, res, ox, oy), [(-3.63, 2.14), (-3.63, 1.0)])
    assert not tp.check_trajectory(-3.62892867, 2.13774521, -2.04744714, 0, 0, 0,
                                   0.0, 0.0, 0.0)
    # in free space both agree, costs included
    free = np.full((140, 80), 7, dtype=np.uint8)
    assert native.footprint_costs(free, ox, oy, res, fp, *pose, exact=True)[0] == 7.0
