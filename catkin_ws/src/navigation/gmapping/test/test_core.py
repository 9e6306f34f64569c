"""slam_gmapping's core without a master: the scan matcher finds a known offset, motion model
statistics, weights / Neff / resampling, map integration, and a whole filter run in a synthetic
room with drifting odometry."""
import math

import numpy as np
import pytest

import segment_lidar
from gmapping import native
from gmapping.motion import absolute_difference, draw_from_motion
from gmapping.params import ParamError, SlamParams, validate
from gmapping.rbpf import GridSlam
from gmapping.resample import entropy, low_variance_indices, neff, normalize_log_weights

# a 6 x 4 m room with a box and a wall stub: segments (x0, y0, x1, y1)
SEGMENTS = np.array([
    (-3, -2, 3, -2), (3, -2, 3, 2), (3, 2, -3, 2), (-3, 2, -3, -2),
    (0.5, -0.5, 1.0, -0.5), (1.0, -0.5, 1.0, 0.2), (1.0, 0.2, 0.5, 0.2), (0.5, 0.2, 0.5, -0.5),
    (-1.5, 2, -1.5, 1.0),
], dtype=float) + 0.0137     # walls off the cell borders, as real walls are
ANGLES = np.linspace(-math.pi, math.pi, 360, endpoint=False)


def raycast(pose, max_range=8.0):
    """Ranges of a 360-beam lidar at pose against SEGMENTS."""
    return segment_lidar.raycast(SEGMENTS, ANGLES, pose, max_range)


def single_map(pose, delta=0.05):
    grids = native.Grids(1, 120, 160, (-4.0, -3.0), delta)
    scan = native.Scan(raycast(pose), ANGLES, 7.99, 7.99)
    assert native.integrate(grids, np.array([pose]), scan) == 0
    return grids


def matcher(**kw):
    p = SlamParams(**kw)
    return native.GmMatcherParams(p.sigma, p.kernelSize, p.lsigma, p.lskip, p.lstep, p.astep, p.iterations,
                                  0.1, -0.5, p.minimumScore)


def test_integration_marks_walls_and_free_space():
    g = single_map((0.0, 0.0, 0.0))
    occ = np.where(g.visits[0] > 0, g.hits[0] / np.maximum(g.visits[0], 1), -1)
    cell = lambda x, y: (int((y - g.origin[1]) / 0.05), int((x - g.origin[0]) / 0.05))   # noqa: E731
    assert occ[cell(3.02, 1.5)] > 0.5           # east wall (x = 3.0137)
    assert occ[cell(-2.98, 0.51)] > 0.5         # west wall (x = -2.9863)
    assert occ[cell(-1.0, -1.0)] == 0.0         # open floor
    assert occ[cell(3.5, 0.0)] == -1            # behind the wall: unknown


@pytest.mark.parametrize('offset', [(0.08, -0.06, 0.04), (-0.05, 0.07, -0.06)])
def test_scan_matcher_finds_a_known_offset(offset):
    truth = np.array([0.2, -0.3, 0.3])
    g = single_map(truth)
    scan = native.Scan(raycast(truth), ANGLES, 7.99, 7.99)
    start = truth + np.array(offset)
    poses, scores, lik = native.optimize(g, start[None, :], scan, matcher())
    err, err0 = poses[0] - truth, start - truth
    # gmapping's score (sigma 0.05) is nearly flat within one cell: the matcher recovers the
    # offset to about a cell (0.05 m), the particle filter averages the rest
    assert math.hypot(err[0], err[1]) < 0.6 * math.hypot(err0[0], err0[1]) and math.hypot(err[0], err[1]) < 0.06, \
        'scan matcher ended %.3f m off (started %.3f m off)' % (math.hypot(err[0], err[1]),
                                                                math.hypot(err0[0], err0[1]))
    assert abs(err[2]) < 0.02
    before = native.score(g, 0, start, scan, matcher())
    assert scores[0] > before


def test_minimum_score_keeps_the_odometry_pose():
    truth = np.array([0.0, 0.0, 0.0])
    g = single_map(truth)
    scan = native.Scan(raycast(truth), ANGLES, 7.99, 7.99)
    start = np.array([[0.05, 0.0, 0.0]])
    poses, scores, _ = native.optimize(g, start, scan, matcher(minimumScore=1e9))
    assert np.array_equal(poses, start)


def test_motion_model_statistics():
    rng = np.random.default_rng(3)
    n = 20000
    poses = np.zeros((n, 3))
    out = draw_from_motion(poses, (0, 0, 0), (1.0, 0.0, 0.0), 0.1, 0.2, 0.1, 0.2, rng)
    assert out[:, 0].mean() == pytest.approx(1.0, abs=0.005)
    assert out[:, 0].std() == pytest.approx(0.1, rel=0.05)            # srr * 1 m
    assert out[:, 2].std() == pytest.approx(0.2, rel=0.05)            # srt * 1 m
    out = draw_from_motion(poses, (0, 0, 0), (0.0, 0.0, 0.5), 0.1, 0.2, 0.1, 0.2, rng)
    assert out[:, 2].mean() == pytest.approx(0.5, abs=0.005)
    assert out[:, 2].std() == pytest.approx(0.1, rel=0.05)            # stt * 0.5 rad
    assert out[:, 0].std() == pytest.approx(0.05, rel=0.05)           # str * 0.5 rad
    # motion is applied in each particle's own frame
    turned = draw_from_motion(np.array([[1.0, 1.0, math.pi / 2]]), (0, 0, 0), (1.0, 0, 0), 0, 0, 0, 0, rng)
    assert turned[0] == pytest.approx([1.0, 2.0, math.pi / 2])
    assert absolute_difference(np.array([1.0, 2.0, math.pi / 2]), np.array([1.0, 1.0, math.pi / 2])) == \
        pytest.approx([1.0, 0.0, 0.0])


def test_weights_neff_and_resampling():
    w = normalize_log_weights([0.0, 0.0, 0.0, 0.0], 3.0)
    assert neff(w) == pytest.approx(4.0) and entropy(w) == pytest.approx(math.log(4))
    w = normalize_log_weights([0.0, -1e6, -1e6, -1e6], 3.0)
    assert neff(w) == pytest.approx(1.0)
    rng = np.random.default_rng(0)
    w = np.array([0.5, 0.25, 0.125, 0.125])
    counts = np.zeros(4)
    for _ in range(4000):
        counts += np.bincount(low_variance_indices(w, rng), minlength=4)
    assert counts / counts.sum() == pytest.approx(w, abs=0.01)
    idx = low_variance_indices(np.array([0.0, 1.0, 0.0]), rng)
    assert idx.tolist() == [1, 1, 1]


def test_filter_corrects_drifting_odometry_in_a_room():
    rng = np.random.default_rng(7)
    p = SlamParams(particles=10, linearUpdate=0.1, angularUpdate=0.2, xmin=-5, ymin=-5, xmax=5, ymax=5)
    slam = GridSlam(p, seed=1)
    truth, odom = np.array([-2.0, -1.0, 0.0]), np.array([-2.0, -1.0, 0.0])
    errors = []
    for k in range(140):
        v, w = 0.05, (0.04 if k < 70 else -0.04)
        step = np.array([v, 0.0, w])
        c, s = math.cos(truth[2]), math.sin(truth[2])
        truth = truth + np.array([c * step[0], s * step[0], step[2]])
        # odometry: 5 % scale error and a yaw bias
        c, s = math.cos(odom[2]), math.sin(odom[2])
        odom = odom + np.array([c * step[0] * 1.05, s * step[0] * 1.05, step[2] + 0.0015])
        ranges = raycast(truth) + rng.normal(0, 0.01, len(ANGLES))
        if slam.process(odom, ranges, ANGLES, 7.99, 7.99, k * 0.1):
            best = slam.best_pose()
            # the map frame starts at the first odometry pose, which equals the truth here
            errors.append(math.hypot(best[0] - truth[0], best[1] - truth[1]))
    odom_err = math.hypot(odom[0] - truth[0], odom[1] - truth[1])
    assert slam.count > 20
    assert odom_err > 0.25, 'the test needs drifting odometry (%.3f m)' % odom_err
    assert max(errors[-10:]) < min(0.1, odom_err / 3), \
        'SLAM error %.3f m (odometry %.3f m)' % (max(errors[-10:]), odom_err)
    grid, origin = slam.occupancy()
    assert (grid == 100).sum() > 200 and (grid == 0).sum() > 2000
    traj = slam.best_trajectory()
    assert len(traj) == slam.count and traj[0][0] == 0.0


def test_bad_parameters_are_named():
    with pytest.raises(ParamError, match='~delta'):
        validate(SlamParams(delta=0.0))
    with pytest.raises(ParamError, match='~particles'):
        validate(SlamParams(particles=0))
    validate(SlamParams())
