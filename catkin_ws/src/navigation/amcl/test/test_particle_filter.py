"""Particle filter: KLD sample counts, resampling, recovery, clusters; convergence on a
synthetic map."""
import numpy as np
import pytest

from amcl.localizer import Config, Localizer
from amcl.pf import ParticleFilter, resample_limit, resample_limits
from amcl.sensors import angle_diff
from amcl_synthetic import room_map, scan


def test_kld_limit_formula():
    # k bins, err 0.01, z 0.99 as passed by amcl (the quantile itself is not looked up)
    k = 50
    b = 2 / (9 * 49)
    want = int(np.ceil(49 / 0.02 * (1 - b + np.sqrt(b) * 0.99) ** 3))
    assert resample_limit(k, 0.01, 0.99, 100, 5000) == want
    assert resample_limit(1, 0.01, 0.99, 100, 5000) == 5000
    assert resample_limit(2, 0.01, 0.99, 100, 5000) == 100          # clamped to min
    assert resample_limit(10000, 0.01, 0.99, 100, 5000) == 5000     # clamped to max
    ks = np.arange(0, 300)
    assert list(resample_limits(ks, 0.01, 0.99, 100, 5000)) == [resample_limit(k, 0.01, 0.99, 100, 5000) for k in ks]


def test_concentrated_set_shrinks_to_min_particles():
    pf = ParticleFilter(100, 5000, rng=np.random.default_rng(3))
    pf.init([1.0, 1.2, 0.1], np.diag([1e-4, 1e-6, 1e-6]))     # two bins (x across 1.0)
    assert pf.count == 5000
    # as pf.c: the sample that takes the count above the limit (min_particles) is kept
    assert pf.update_resample() == 101


def test_spread_set_keeps_kld_count():
    pf = ParticleFilter(100, 5000, rng=np.random.default_rng(4))
    pf.init([0.0, 0.0, 0.0], np.diag([1.0, 1.0, 0.5]))
    m = pf.update_resample()
    keys = np.unique(np.floor(pf.poses / [0.5, 0.5, np.radians(10)]), axis=0)
    # stopped at the first sample above the limit for the bins seen so far
    assert m == resample_limit(len(keys), 0.01, 0.99, 100, 5000) + 1 or m == 5000
    assert 1000 < m <= 5000


def test_resampling_follows_weights():
    pf = ParticleFilter(4000, 4000, rng=np.random.default_rng(5))
    pf.poses = np.array([[0.0, 0, 0], [5.0, 0, 0], [10.0, 0, 0], [15.0, 0, 0]])
    pf.weights = np.array([0.1, 0.2, 0.3, 0.4])
    pf.update_resample()
    frac = [np.mean(pf.poses[:, 0] == x) for x in (0, 5, 10, 15)]
    assert frac == pytest.approx([0.1, 0.2, 0.3, 0.4], abs=0.025)
    assert np.allclose(pf.weights, 1 / 4000)


def test_recovery_injects_random_poses_when_likelihood_drops():
    pf = ParticleFilter(1000, 1000, alpha_slow=0.001, alpha_fast=0.1, random_pose=lambda n: np.full((n, 3), 99.0),
                        rng=np.random.default_rng(6))
    pf.init([0, 0, 0], np.diag([0.01, 0.01, 0.01]))
    pf.update_sensor(lambda p, w: w * 1.0)          # sets w_slow = w_fast
    for _ in range(20):
        pf.update_sensor(lambda p, w: w * 0.01)     # the measurements suddenly fit badly
    w_diff = 1 - pf.w_fast / pf.w_slow
    assert w_diff > 0.5
    pf.update_resample()
    assert np.mean(pf.poses[:, 0] == 99.0) == pytest.approx(w_diff, abs=0.06)
    assert pf.w_slow == 0 and pf.w_fast == 0


def test_selective_resampling_skips_when_weights_are_even():
    pf = ParticleFilter(100, 500, selective_resampling=True, rng=np.random.default_rng(7))
    pf.init([0, 0, 0], np.diag([1.0, 1.0, 1.0]))
    before = pf.poses.copy()
    assert pf.update_resample() == 500 and np.array_equal(pf.poses, before)


def test_two_clusters_heaviest_first():
    pf = ParticleFilter(100, 200, rng=np.random.default_rng(8))
    pf.poses = np.vstack([np.tile([1.0, 1.0, 0.1], (100, 1)), np.tile([4.0, 1.0, 0.1], (100, 1))])
    pf.weights = np.r_[np.full(100, 0.3 / 100), np.full(100, 0.7 / 100)]
    cl = pf.cluster_stats()
    assert len(cl) == 2
    assert cl[0].weight == pytest.approx(0.7) and cl[0].mean[0] == pytest.approx(4.0)


def test_min_above_max_rejected():
    with pytest.raises(ValueError, match='min_particles'):
        ParticleFilter(600, 500)


def drive(loc, gmap, truth, steps, rng, odom_noise=0.02):
    """Move the true robot (forward, turning back into the room near walls), feed noisy
    odometry and scans; return the (position, yaw) errors of every filter update."""
    odom = np.array([0.0, 0.0, 0.0])
    errs = []
    for k in range(steps):
        v, w = 0.2, (0.15 if (k // 10) % 2 else -0.1)
        nxt = truth + [v * np.cos(truth[2]), v * np.sin(truth[2]), w]
        if not (0.6 < nxt[0] < 5.4 and 0.4 < nxt[1] < 3.6) or (nxt[0] > 3.7 and nxt[1] > 1.2):
            v, w = 0.0, 0.6
        truth = truth + [v * np.cos(truth[2]), v * np.sin(truth[2]), w]
        d = v * (1 + rng.normal(0, odom_noise))
        odom = odom + [d * np.cos(odom[2]), d * np.sin(odom[2]), w * (1 + rng.normal(0, odom_noise))]
        res = loc.process(odom, scan(gmap, truth, noise=0.01, rng=rng))
        if res.updated:
            errs.append((np.hypot(*(res.pose[:2] - truth[:2])), abs(float(angle_diff(res.pose[2], truth[2])))))
    return errs


def test_converges_from_half_a_metre_and_20_degrees_off():
    rng = np.random.default_rng(9)
    gmap = room_map()
    truth = np.array([2.5, 2.0, 0.0])
    loc = Localizer(Config(update_min_d=0.1, update_min_a=0.2), rng=rng)
    loc.set_map(gmap, initial_pose=truth + [0.35, -0.35, np.radians(20)])
    errs = drive(loc, gmap, truth, 25, rng)
    final = np.array(errs[-5:])
    assert final[:, 0].max() < 0.1 and final[:, 1].max() < 0.1, errs


def test_global_localization_on_the_synthetic_room():
    rng = np.random.default_rng(10)
    gmap = room_map()
    truth = np.array([2.0, 1.5, 0.5])
    loc = Localizer(Config(update_min_d=0.1, update_min_a=0.2, max_particles=5000), rng=rng)
    loc.set_map(gmap)
    loc.global_localization()
    errs = drive(loc, gmap, truth, 60, rng)
    final = np.array(errs[-3:])
    assert final[:, 0].max() < 0.25 and final[:, 1].max() < 0.25, errs
