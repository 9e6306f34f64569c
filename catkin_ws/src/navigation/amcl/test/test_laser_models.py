"""Laser models: the true pose scores best; likelihood field against a per-beam loop."""
import numpy as np
import pytest

from amcl.sensors import LaserModel
from amcl_synthetic import room_map, scan

TRUE = np.array([2.5, 2.0, 0.4])


def poses_around(true):
    offsets = np.array([[0, 0, 0], [0.3, 0, 0], [0, -0.3, 0], [0, 0, 0.3], [-0.2, 0.2, -0.2]])
    return true + offsets


@pytest.mark.parametrize('model', ['likelihood_field', 'beam', 'likelihood_field_prob'])
def test_true_pose_scores_best(model):
    m = room_map()
    m.update_cspace(2.0)
    data = scan(m, TRUE, noise=0.01)
    lm = LaserModel(model, max_beams=60)
    w = lm.weights(m, poses_around(TRUE), np.ones(5), data)
    assert np.argmax(w) == 0, w
    assert np.all(w > 0)


def test_likelihood_field_against_loop():
    m = room_map()
    m.update_cspace(2.0)
    data = scan(m, TRUE, noise=0.02)
    data.ranges[5] = data.range_max          # a max-range reading is skipped
    data.ranges[17] = np.nan
    lm = LaserModel('likelihood_field', max_beams=30, sigma_hit=0.2, z_hit=0.95, z_rand=0.05)
    poses = poses_around(TRUE)
    got = lm.weights(m, poses, np.full(5, 0.5), data)
    step = (360 - 1) // (30 - 1)
    for k, p in enumerate(poses):
        total = 1.0
        for i in range(0, 360, step):
            r = data.ranges[i]
            if not np.isfinite(r) or r >= data.range_max:
                continue
            hx = p[0] + r * np.cos(p[2] + data.angles[i])
            hy = p[1] + r * np.sin(p[2] + data.angles[i])
            ci, cj = int(np.floor(hx / 0.05)), int(np.floor(hy / 0.05))
            z = m.occ_dist[cj, ci] if 0 <= ci < m.width and 0 <= cj < m.height else 2.0
            pz = 0.95 * np.exp(-z * z / (2 * 0.04)) + 0.05 / 12.0
            total += pz ** 3
        assert got[k] == pytest.approx(0.5 * total, rel=1e-9)


def test_beam_indices_like_the_original():
    assert len(LaserModel(max_beams=30).beam_indices(360)) == 30
    assert list(LaserModel(max_beams=30).beam_indices(10)) == list(range(10))


def test_laser_offset_on_the_robot():
    m = room_map()
    m.update_cspace(2.0)
    lp = (0.1, 0.0, np.pi)       # mounted backwards, 10 cm ahead
    data = scan(m, TRUE, laser_pose=lp)
    lm = LaserModel(max_beams=60)
    w = lm.weights(m, poses_around(TRUE), np.ones(5), data)
    assert np.argmax(w) == 0


def test_beamskip_ignores_an_unmapped_obstacle():
    m = room_map()
    m.update_cspace(2.0)
    data = scan(m, TRUE, noise=0.01)
    data.ranges[100:160] = 0.4      # a person in front of the laser
    lm = LaserModel('likelihood_field_prob', max_beams=60, do_beamskip=True)
    w = lm.weights(m, poses_around(TRUE), np.ones(5), data)
    assert np.argmax(w) == 0


def test_bad_model_rejected():
    with pytest.raises(ValueError, match='laser_model_type'):
        LaserModel('sonar')
