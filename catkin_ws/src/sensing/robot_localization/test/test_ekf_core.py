"""Unit tests of the EKF core, the sensor front-end and the runner (no roscore)."""
import math

import numpy as np
import pytest

from drive_sim import drive, truth_at
from robot_localization.ekf import Ekf, Measurement, X, Y, YAW, VX, VYAW, ROLL, PITCH, normalize_angle
from robot_localization.sensors import (SensorConfig, twist_measurement, pose_measurement,
                                        imu_angular_measurement, config_warnings,
                                        covariance_warnings, relative_pose)
from robot_localization.filter_runner import (FilterRunner, timestamp_before_previous,
                                              timestamp_before_reset)

ODOM_CONFIG = [False] * 6 + [True, True, False, False, False, True] + [False] * 3
IMU_CONFIG = [False] * 11 + [True] + [False] * 3


def cov6(diag):
    return np.diag(diag)


def run_fusion(events, use_imu=True):
    odom = SensorConfig('odom0', 'odom', 'odom', ODOM_CONFIG)
    imu = SensorConfig('imu0', 'imu', 'imu/data', IMU_CONFIG)
    runner = FilterRunner(Ekf(), sensor_timeout=1.0 / 30.0)
    track = []
    next_publish = 0.0
    for kind, t, data in events:
        if kind == 'odom':
            _, _, _, v, w = data
            runner.enqueue(twist_measurement(odom, t, (v, 0.0, 0.0, 0.0, 0.0, w),
                                             cov6([1e-3, 1e-3, 1e6, 1e6, 1e6, 0.1]), two_d=True))
        elif use_imu:
            runner.enqueue(imu_angular_measurement(imu, t, (0.0, 0.0, data),
                                                   np.diag([1e-4, 1e-4, 1e-4]), two_d=True))
        if t >= next_publish:
            runner.integrate(t)
            track.append((t, runner.ekf.x[X], runner.ekf.x[Y], runner.ekf.x[YAW]))
            next_publish += 1.0 / 30.0
    return track


def errors(track, truth):
    e = [math.hypot(x - truth_at(truth, t)[0], y - truth_at(truth, t)[1]) for t, x, y, _ in track]
    return float(np.mean(e)), e[-1]


def test_fused_pose_beats_wheel_odometry_on_60s_drive_with_slip():
    truth, events = drive(60.0)
    fused = run_fusion(events)
    wheel = [(t, d[0], d[1], d[2]) for k, t, d in events if k == 'odom']
    fused_mean, fused_final = errors(fused, truth)
    wheel_mean, wheel_final = errors(wheel, truth)
    print('60 s drive with wheel slip: position error wheel odometry mean %.3f m final %.3f m; '
          'EKF (odom + IMU yaw rate) mean %.3f m final %.3f m'
          % (wheel_mean, wheel_final, fused_mean, fused_final))
    assert fused_mean < 0.5 * wheel_mean
    assert fused_final < 0.5 * wheel_final


def test_wheel_only_fusion_tracks_wheel_odometry():
    truth, events = drive(10.0, seed=3)
    fused = run_fusion(events, use_imu=False)
    wheel = {round(t, 3): d for k, t, d in events if k == 'odom'}
    t, x, y, _ = fused[-1]
    ox, oy = min(wheel.items(), key=lambda kv: abs(kv[0] - t))[1][:2]
    assert math.hypot(x - ox, y - oy) < 0.05


def test_prediction_constant_velocity_3d():
    ekf = Ekf()
    ekf.process(Measurement(0.0, [1.0, 0.5], np.diag([1e-6, 1e-6]), [VX, VYAW]))
    ekf.predict(1.0)
    # 1 s of 1 m/s with yaw rate 0.5 rad/s (Euler steps of the model: one step)
    assert ekf.x[X] == pytest.approx(1.0)
    assert ekf.x[YAW] == pytest.approx(0.5)
    ekf.predict(2.0)
    assert ekf.x[X] == pytest.approx(1.0 + math.cos(0.5))
    assert ekf.x[Y] == pytest.approx(math.sin(0.5))


def test_jacobian_matches_numeric_derivative():
    ekf = Ekf()
    rng = np.random.default_rng(1)
    ekf.x = rng.normal(size=15) * 0.5
    ekf.x[PITCH] = 0.3
    dt = 0.1
    F, J = ekf.transfer(dt)
    base = ekf.x.copy()
    Jn = np.zeros((15, 15))
    for i in range(15):
        h = 1e-6
        ekf.x = base.copy()
        ekf.x[i] += h
        Fp, _ = ekf.transfer(dt)
        fp = Fp @ ekf.x
        ekf.x = base.copy()
        ekf.x[i] -= h
        Fm, _ = ekf.transfer(dt)
        fm = Fm @ ekf.x
        Jn[:, i] = (fp - fm) / (2 * h)
    assert np.allclose(J, Jn, atol=1e-6)


def test_angles_wrapped_and_mahalanobis_gate():
    ekf = Ekf()
    ekf.process(Measurement(0.0, [3.1], [[0.01]], [YAW]))
    ekf.process(Measurement(0.1, [-3.1], [[0.01]], [YAW]))
    assert abs(ekf.x[YAW]) > 3.0          # averaged across the wrap, not through 0
    before = ekf.x.copy()
    ok = ekf.process(Measurement(0.2, [5.0], [[1e-4]], [X], threshold=3.0))
    assert not ok and ekf.rejected == 1
    assert ekf.x[X] == pytest.approx(before[X], abs=1e-6)


def test_bad_covariances_are_sanitised_and_reported():
    ekf = Ekf()
    ekf.process(Measurement(0.0, [0.0], [[1.0]], [X]))
    ekf.process(Measurement(0.1, [1.0], [[-0.5]], [X]))   # negative -> |.| = 0.5
    assert np.all(np.isfinite(ekf.x)) and np.all(np.isfinite(ekf.P))
    assert 0.0 < ekf.x[X] < 1.0
    ekf.process(Measurement(0.2, [1.0], [[0.0]], [X]))    # zero -> 1e-9: snaps to it
    assert ekf.x[X] == pytest.approx(1.0, abs=1e-3)
    w = covariance_warnings('odom', 'twist', np.diag([-1.0, 0.0, 1e4, 1.0, 1.0, 1.0]),
                            [True, True, True, False, False, False], 6)
    assert any('was negative' in s for s in w)
    assert any('was zero. This will be replaced with a small value' in s for s in w)
    assert any('extremely large' in s for s in w)


def test_out_of_order_and_reset_stamps_are_ignored():
    runner = FilterRunner()
    assert runner.accept_stamp('odom', 1.0)
    assert runner.accept_stamp('odom', 1.0)
    assert not runner.accept_stamp('odom', 0.5)
    assert runner.warnings[-1] == ('odom_timestamp', timestamp_before_previous('odom'))
    runner.set_pose(2.0, [1, 2, 0, 0, 0, 0.5], np.eye(6) * 0.01)
    assert runner.ekf.x[X] == 1 and runner.ekf.x[YAW] == 0.5 and runner.ekf.initialized
    assert not runner.accept_stamp('odom', 1.5)
    assert runner.warnings[-1] == ('odom_timestamp', timestamp_before_reset('odom'))
    assert runner.accept_stamp('odom', 2.5)


def test_sensor_timeout_predicts_forward():
    runner = FilterRunner(sensor_timeout=0.1)
    runner.enqueue(Measurement(0.0, [1.0], [[1e-6]], [VX]))
    assert runner.integrate(0.0)
    runner.integrate(0.05)
    assert runner.ekf.x[X] == 0.0
    runner.integrate(1.0)
    assert runner.ekf.x[X] == pytest.approx(1.0)


def test_two_d_mode_pins_z_roll_pitch():
    cfg = SensorConfig('pose0', 'pose', 'pose', [True] * 6 + [False] * 9)
    m = pose_measurement(cfg, 0.0, (1, 2, 3, 0.1, 0.2, 0.3), np.eye(6) * 0.01, two_d=True)
    got = dict(zip(m.indices.tolist(), m.z.tolist()))
    assert got[0] == 1 and got[2] == 0.0 and got[ROLL] == 0.0 and got[PITCH] == 0.0 and got[YAW] == 0.3


def test_differential_and_relative_modes():
    cfg = SensorConfig('odom0', 'odom', 'odom', [True, True, False, False, False, True] + [False] * 9,
                       differential=True)
    assert pose_measurement(cfg, 0.0, (1, 1, 0, 0, 0, math.pi / 2), np.eye(6) * 0.01) is None
    m = pose_measurement(cfg, 0.5, (1, 1.5, 0, 0, 0, math.pi / 2 + 0.1), np.eye(6) * 0.01)
    got = dict(zip(m.indices.tolist(), m.z.tolist()))
    assert got[VX] == pytest.approx(1.0) and abs(got[7]) < 1e-9 and got[VYAW] == pytest.approx(0.2)
    rel = SensorConfig('pose0', 'pose', 'pose', [True] * 6 + [False] * 9, relative=True)
    m = pose_measurement(rel, 0.0, (5, 5, 0, 0, 0, 1.0), np.eye(6))
    assert np.allclose(m.z, 0.0)
    assert relative_pose((1, 0, 0, 0, 0, math.pi / 2), (1, 1, 0, 0, 0, math.pi / 2))[0] == pytest.approx(1.0)


def test_config_warnings():
    imu = SensorConfig('imu0', 'imu', 'imu/data', [True] + [False] * 14)
    assert any('position entries in parameter imu0_config' in s for s in config_warnings(imu))
    none = SensorConfig('odom0', 'odom', 'odom', [False] * 15)
    assert any('all update variables are false' in s for s in config_warnings(none))


def test_normalize_angle():
    assert normalize_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert normalize_angle(-3 * math.pi / 2) == pytest.approx(math.pi / 2)


def _not_diagonal(cov):
    """The same covariance with a negligible off-diagonal term: the core's batch update path."""
    c = np.array(cov, float)
    if len(c) > 1:
        c[0, 1] = c[1, 0] = 1e-15
    return c


def test_sequential_update_equals_batch_update():
    rng = np.random.default_rng(5)
    A = rng.normal(size=(15, 15))
    P0 = A @ A.T + np.eye(15)
    for idx, r in (([6, 7, 11], [0.1, 0.2, 0.05]), ([0, 1, 5, 2, 3, 4], [1e-3, 1e-3, 0.01, 1e-6, 1e-6, 1e-6])):
        a, b = Ekf(), Ekf()
        for e in (a, b):
            e.x = np.arange(15) * 0.01
            e.P = P0.copy()
            e.initialized = True
        z = np.array([0.5] * len(idx))
        assert a.correct(Measurement(0.0, z, np.diag(r), idx))                   # sequential
        assert b.correct(Measurement(0.0, z, _not_diagonal(np.diag(r)), idx))    # batch
        assert np.allclose(a.x, b.x, atol=1e-9)
        assert np.allclose(a.P, b.P, atol=1e-9)


def test_gate_is_the_same_in_both_paths():
    for path in ('seq', 'batch'):
        e = Ekf()
        e.initialized, e.last_time = True, 0.0
        e.P = np.eye(15)
        cov = np.eye(2) if path == 'seq' else _not_diagonal(np.eye(2))
        m = Measurement(0.0, [2.0, 2.1], cov, [X, Y], threshold=2.0)   # d^2 = 2 + 2.205 >= 4
        ok = e.correct(m)
        assert not ok and e.rejected == 1
