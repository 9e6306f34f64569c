"""The accelerometer's ellipsoid calibration (diploma section 3.2), without ROS: synthetic
readings M = A m + b + noise of gravity m seen in random orientations; the fit recovers the
known A and b, the header round-trips, bad input gets one clear line."""
import os
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), 'src'))
from space_scanner_hw import accel_calibration as ac  # noqa: E402

A_TRUE = np.array([[1.04, 0.02, -0.015],
                   [0.02, 0.97, 0.01],
                   [-0.015, 0.01, 1.02]])
B_TRUE = np.array([0.35, -0.22, 0.48])


def gravity_directions(n, rng):
    v = rng.normal(size=(n, 3))
    return ac.G * v / np.linalg.norm(v, axis=1, keepdims=True)


def readings(n=400, noise=0.01, seed=1, a=A_TRUE, b=B_TRUE):
    rng = np.random.default_rng(seed)
    m = gravity_directions(n, rng)
    return m @ a.T + b + rng.normal(scale=noise, size=(n, 3)), m


def test_recovers_a_known_ellipsoid():
    samples, truth = readings()
    a, b = ac.fit_ellipsoid(samples)
    assert np.allclose(a, A_TRUE, atol=2e-3), a
    assert np.allclose(b, B_TRUE, atol=5e-3), b
    corrected = ac.correct(samples, np.linalg.inv(a), b)
    assert np.max(np.abs(np.linalg.norm(corrected, axis=1) - ac.G)) < 0.05
    assert np.max(np.abs(corrected - truth)) < 0.06      # symmetric A: the true vectors back


def test_exact_without_noise_and_from_few_orientations():
    samples, _ = readings(n=30, noise=0.0, seed=3)
    a, b = ac.fit_ellipsoid(samples)
    assert np.allclose(a, A_TRUE, atol=1e-9) and np.allclose(b, B_TRUE, atol=1e-9)


def test_ideal_sensor_gives_identity():
    samples, _ = readings(noise=0.0, a=np.eye(3), b=np.zeros(3))
    a, b = ac.fit_ellipsoid(samples)
    assert np.allclose(a, np.eye(3), atol=1e-9) and np.allclose(b, 0, atol=1e-9)


def test_compose_with_the_calibration_applied_while_recording():
    """Readings taken through a first calibration (C, d) still give the raw sensor's (A, b)."""
    raw, _ = readings(noise=0.0)
    c = np.diag([1.1, 0.9, 1.0])
    d = np.array([0.1, 0.0, -0.2])
    seen = ac.correct(raw, c, d)
    a2, b2 = ac.fit_ellipsoid(seen)
    a_inv, b = ac.compose(c, d, a2, b2)
    assert np.max(np.abs(ac.residuals(raw, a_inv, b))) < 1e-9


def test_header_round_trip():
    a_inv = np.linalg.inv(A_TRUE)
    text = ac.header_text(a_inv, B_TRUE, 'test.bag (imu/data_raw)', 'line one\nline two')
    assert 'const float ACCEL_CAL_MATRIX[3][3]' in text and 'const float ACCEL_CAL_OFFSET[3]' in text
    assert '// line two' in text
    m, b = ac.parse_header(text)
    assert np.allclose(m, a_inv, rtol=1e-8) and np.allclose(b, B_TRUE)


def test_the_firmwares_default_header_is_the_identity():
    path = os.path.join(HERE, *['..'] * 5, 'firmware', 'sketches', 'space_scanner_base', 'accel_calibration.h')
    with open(path) as f:
        m, b = ac.parse_header(f.read())
    assert np.array_equal(m, np.eye(3)) and np.array_equal(b, np.zeros(3))


@pytest.mark.parametrize('samples, words', [
    (np.zeros((5, 3)), 'at least 9 samples'),
    (np.zeros((20, 2)), 'N x 3'),
    (np.full((20, 3), np.nan), 'NaN'),
    (np.tile([0.0, 0.0, 9.8], (50, 1)), 'same reading'),
    # a sensor turned about one axis only: readings in a plane
    (np.column_stack([9.8 * np.cos(np.linspace(0, 6, 50)), 9.8 * np.sin(np.linspace(0, 6, 50)), np.zeros(50)]),
     'too few orientations'),
])
def test_bad_input_one_clear_line(samples, words):
    with pytest.raises(ac.CalibrationError) as e:
        ac.fit_ellipsoid(samples)
    assert words in str(e.value) and '\n' not in str(e.value)


def test_coverage_figure():
    samples, _ = readings(noise=0.0)
    assert ac.coverage(samples, B_TRUE) == pytest.approx(1 / np.sqrt(3), abs=0.05)


def test_cli_bad_bag_path_one_line(tmp_path):
    script = os.path.join(os.path.dirname(HERE), 'scripts', 'calibrate_accel')
    env = dict(os.environ, PYTHONPATH=os.path.join(os.path.dirname(HERE), 'src') + os.pathsep
               + os.environ.get('PYTHONPATH', ''))
    r = subprocess.run(['/usr/bin/python3', script, '--bag', str(tmp_path / 'missing.bag')],
                       capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode == 1
    assert r.stderr.startswith('calibrate_accel: cannot read bag') and r.stderr.count('\n') == 1, r.stderr
