"""Odometry models: means and spreads of the sampled poses against the formulas."""
import numpy as np
import pytest

from amcl.sensors import OdomModel, angle_diff

N = 200000


def run(model, delta, pose_theta=0.3, **alphas):
    rng = np.random.default_rng(2)
    m = OdomModel(model, rng=rng, **alphas)
    poses = np.zeros((N, 3))
    poses[:, 2] = pose_theta
    new = np.array([delta[0], delta[1], pose_theta + delta[2]])
    return m.sample(poses, new, np.asarray(delta, dtype=float))


@pytest.mark.parametrize('model', ['diff', 'diff-corrected', 'omni', 'omni-corrected'])
def test_noise_free_motion_is_exact(model):
    d = (0.3 * np.cos(0.3), 0.3 * np.sin(0.3), 0.1)
    p = run(model, d, alpha1=0, alpha2=0, alpha3=0, alpha4=0, alpha5=0)
    assert np.allclose(p[:, 0], d[0]) and np.allclose(p[:, 1], d[1])
    assert np.allclose(p[:, 2], 0.4)


def test_diff_corrected_translation_spread():
    # straight drive of 0.5 m: trans sd = sqrt(alpha3) * 0.5, rot1/rot2 sd = sqrt(alpha2) * 0.5
    d = (0.5 * np.cos(0.3), 0.5 * np.sin(0.3), 0.0)
    p = run('diff-corrected', d, alpha1=0.0, alpha2=0.01, alpha3=0.04, alpha4=0.0)
    along = p[:, 0] * np.cos(0.3) + p[:, 1] * np.sin(0.3)
    assert along.mean() == pytest.approx(0.5, abs=0.002)
    assert along.std() == pytest.approx(np.sqrt(0.04) * 0.5, rel=0.03)
    dyaw = angle_diff(p[:, 2], 0.3)
    assert dyaw.mean() == pytest.approx(0.0, abs=0.002)
    assert dyaw.std() == pytest.approx(np.sqrt(2 * 0.01) * 0.5, rel=0.03)


def test_diff_uses_variance_as_sigma_like_the_original():
    d = (0.5 * np.cos(0.3), 0.5 * np.sin(0.3), 0.0)
    p = run('diff', d, alpha1=0.0, alpha2=0.0, alpha3=0.04, alpha4=0.0)
    along = p[:, 0] * np.cos(0.3) + p[:, 1] * np.sin(0.3)
    assert along.std() == pytest.approx(0.04 * 0.25, rel=0.03)


def test_diff_rotation_in_place_spread():
    p = run('diff-corrected', (0.0, 0.0, 0.5), alpha1=0.09, alpha2=0.0, alpha3=0.0, alpha4=0.0)
    dyaw = angle_diff(p[:, 2], 0.3)
    assert dyaw.mean() == pytest.approx(0.5, abs=0.003)
    assert dyaw.std() == pytest.approx(0.3 * 0.5, rel=0.03)    # rot2 only: rot1 = 0
    assert np.allclose(p[:, :2], 0.0)


def test_diff_backwards_drive_costs_as_forwards():
    fwd = run('diff-corrected', (0.5 * np.cos(0.3), 0.5 * np.sin(0.3), 0.0), alpha1=0.05, alpha2=0.0,
              alpha3=0.01, alpha4=0.05)
    back = run('diff-corrected', (-0.5 * np.cos(0.3), -0.5 * np.sin(0.3), 0.0), alpha1=0.05, alpha2=0.0,
               alpha3=0.01, alpha4=0.05)
    assert np.std(angle_diff(back[:, 2], 0.3)) == pytest.approx(np.std(angle_diff(fwd[:, 2], 0.3)), rel=0.03)
    assert np.mean(back[:, 0]) == pytest.approx(-0.5 * np.cos(0.3), abs=0.003)


def test_omni_corrected_strafe_spread():
    d = (0.4 * np.cos(0.3), 0.4 * np.sin(0.3), 0.0)
    p = run('omni-corrected', d, alpha1=0.0, alpha2=0.0, alpha3=0.0, alpha4=0.0, alpha5=0.09)
    lateral = -p[:, 0] * np.sin(0.3) + p[:, 1] * np.cos(0.3)
    assert lateral.mean() == pytest.approx(0.0, abs=0.002)
    assert lateral.std() == pytest.approx(0.3 * 0.4, rel=0.03)


def test_unknown_model_rejected():
    with pytest.raises(ValueError, match='odom_model_type'):
        OdomModel('tank')
