"""Unit tests of the Madgwick core and the per-sample processor (no roscore)."""
import math

import pytest

from imu_sim import simulate, tilt_error_deg, angle_deg, G
from imu_filter_madgwick.filter import (MadgwickFilter, orientation_from_measurement, quat_from_rpy,
                                        quat_to_rpy, FreeFall, FREE_FALL_WARNING)
from imu_filter_madgwick.processor import Params, ImuProcessor, NON_FINITE_WARNING, ZERO_STAMP_WARNING

RATE = 100.0
TOL_DEG = 2.0


def still(_t):
    return (0.0, 0.0, 0.0)


def wobble(t):
    return (0.6 * math.sin(1.3 * t), 0.4 * math.cos(0.9 * t), 0.3)


@pytest.mark.parametrize('roll,pitch', [(15, 0), (0, -15), (10, 10)])
def test_converges_within_2_deg_in_2_s(roll, pitch):
    """Started level, the IMU actually tilted: the accelerometer pulls it in within 2 s."""
    q_true = quat_from_rpy(math.radians(roll), math.radians(pitch), 0.3)
    f = MadgwickFilter(gain=0.1)
    f.set_orientation(quat_from_rpy(0, 0, 0.3))
    err0 = None
    for t, q, gyro, accel, _ in simulate(q_true, still, 2.0, RATE, 0.002, 0.05):
        if err0 is None:
            err0 = tilt_error_deg(f.q, q)
        f.update_imu(gyro, accel, 1.0 / RATE)
    err = tilt_error_deg(f.q, q)
    print('tilt error %.2f deg -> %.2f deg after 2 s' % (err0, err))
    assert err0 > 10.0
    assert err < TOL_DEG, 'tilt error %.2f deg after 2 s of samples' % err


@pytest.mark.parametrize('frame,up', [('enu', (0, 0, 1)), ('nwu', (0, 0, 1)), ('ned', (0, 0, -1))])
def test_tracks_moving_imu_under_noise(frame, up):
    """Initialised from the first sample, tracks a wobbling, yawing IMU with MPU6050-like noise."""
    q0 = quat_from_rpy(0.2, -0.1, 1.0)
    if frame == 'ned':
        q0 = quat_from_rpy(math.pi + 0.2, -0.1, 1.0)
    proc = ImuProcessor(Params(world_frame=frame, use_mag=False))
    worst = 0.0
    for t, q, gyro, accel, _ in simulate(q0, wobble, 20.0, RATE, 0.005, 0.08, seed=3, up=up):
        # the accelerometer reads "up" in the world frame: for NED that is -z
        res = proc.process(1.0 + t, gyro, accel)
        assert res is not None
        if t >= 0.0:
            worst = max(worst, tilt_error_deg_frame(res.orientation, q, up))
    print('%s: worst tilt error %.2f deg over 20 s' % (frame, worst))
    assert worst < TOL_DEG


def tilt_error_deg_frame(q_est, q_true, up):
    from imu_sim import body_vector
    a, b = body_vector(q_est, up), body_vector(q_true, up)
    d = max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b))))
    return math.degrees(math.acos(d))


def test_marg_full_orientation_with_magnetometer():
    q0 = quat_from_rpy(0.1, 0.2, -2.0)
    field = (0.0, 22e-6, -40e-6)       # ENU: north and down components
    proc = ImuProcessor(Params(world_frame='enu', use_mag=True, zeta=0.0))
    worst = 0.0
    for t, q, gyro, accel, mag in simulate(q0, wobble, 10.0, RATE, 0.005, 0.05, mag_world=field):
        res = proc.process(1.0 + t, gyro, accel, mag)
        worst = max(worst, angle_deg(res.orientation, q))
    print('MARG worst full-orientation error %.2f deg' % worst)
    assert worst < TOL_DEG


def test_marg_corrects_yaw():
    q_true = quat_from_rpy(0.0, 0.0, 0.5)
    f = MadgwickFilter(gain=0.1, world_frame='enu')
    f.set_orientation(quat_from_rpy(0, 0, 0.5 + math.radians(15)))
    field = (0.0, 0.3, -0.4)
    for t, q, gyro, accel, mag in simulate(q_true, still, 3.0, RATE, mag_world=field):
        f.update_marg(gyro, accel, mag, 1.0 / RATE)
    assert angle_deg(f.q, q_true) < TOL_DEG


@pytest.mark.parametrize('frame,expected_rp', [('enu', (0, 0)), ('nwu', (0, 0)), ('ned', (180, 0))])
def test_initial_orientation_world_frames(frame, expected_rp):
    q = orientation_from_measurement((0.0, 0.0, G), None, frame)
    r, p, _ = quat_to_rpy(q)
    assert abs(abs(math.degrees(r)) - expected_rp[0]) < 1e-6
    assert abs(math.degrees(p) - expected_rp[1]) < 1e-6


def test_initial_orientation_with_mag_is_exact():
    for frame, field, up in (('enu', (0, 0.3, -0.4), (0, 0, 1)), ('ned', (0.3, 0, 0.4), (0, 0, -1)),
                             ('nwu', (0.3, 0, -0.4), (0, 0, 1))):
        q_true = quat_from_rpy(0.3 if frame != 'ned' else math.pi + 0.3, -0.2, 1.1)
        from imu_sim import body_vector
        accel = body_vector(q_true, tuple(G * c for c in up))
        mag = body_vector(q_true, field)
        q = orientation_from_measurement(accel, mag, frame)
        assert angle_deg(q, q_true) < 1e-6, frame


def test_free_fall_and_zero_accel_keep_state():
    proc = ImuProcessor(Params(use_mag=False))
    assert proc.process(1.0, (0, 0, 0), (0.0, 0.0, 0.0)) is None
    assert proc.warnings[-1] == ('freefall', FREE_FALL_WARNING)
    assert not proc.initialized
    res = proc.process(1.0, (0, 0, 0), (0.0, 0.0, G))
    assert res is not None and proc.initialized
    q_before = proc.filter.q
    # zero acceleration after init: gyro-only integration (zero rates: unchanged)
    assert proc.process(1.01, (0, 0, 0), (0.0, 0.0, 0.0)) is not None
    assert proc.filter.q == pytest.approx(q_before)
    with pytest.raises(FreeFall):
        orientation_from_measurement((0.0, 0.0, 0.05))


@pytest.mark.parametrize('bad', [(float('nan'), 0.0, G), (0.0, float('inf'), G)])
def test_nan_accel_is_rejected_state_kept(bad):
    proc = ImuProcessor(Params(use_mag=False))
    proc.process(1.0, (0, 0, 0), (0.5, 0.0, G))
    q_before, t_before = proc.filter.q, proc.last_time
    assert proc.process(1.01, (0.1, 0, 0), bad) is None
    assert proc.warnings[-1] == ('nonfinite', NON_FINITE_WARNING)
    assert proc.filter.q == q_before and proc.last_time == t_before
    assert proc.process(1.01, (float('nan'), 0, 0), (0, 0, G)) is None
    assert all(math.isfinite(c) for c in proc.filter.q)


def test_zero_stamp_warns_and_does_not_integrate():
    proc = ImuProcessor(Params(use_mag=False))
    proc.process(0.0, (0, 0, 0), (0, 0, G))
    q0 = proc.filter.q
    proc.process(0.0, (0, 0, 1.0), (0, 0, G))
    assert proc.warnings[-1] == ('zerostamp', ZERO_STAMP_WARNING)
    assert proc.filter.q == pytest.approx(q0)


def test_constant_dt_stateless_gravity_and_offsets():
    proc = ImuProcessor(Params(use_mag=False, constant_dt=0.01))
    proc.process(0.0, (0, 0, 0), (0, 0, G))
    proc.process(0.0, (0, 0, 1.0), (0, 0, G))      # zero stamps but constant dt: integrates
    yaw0 = quat_to_rpy(orientation_from_measurement((0, 0, G)))[2]
    assert quat_to_rpy(proc.filter.q)[2] == pytest.approx(yaw0 + 0.01, abs=1e-4)

    st = ImuProcessor(Params(use_mag=False, stateless=True, remove_gravity_vector=True,
                             orientation_stddev=0.1, yaw_offset=0.5, declination=0.2))
    res = st.process(1.0, (0, 0, 5.0), (0.0, 0.0, G))
    res2 = st.process(2.0, (0, 0, 5.0), (0.0, 0.0, G))
    assert res2.filter_orientation == pytest.approx(res.filter_orientation)   # no integration
    assert res.linear_acceleration == pytest.approx((0, 0, 0), abs=1e-9)
    assert res.covariance[0] == pytest.approx(0.01) and res.covariance[1] == 0.0
    dyaw = quat_to_rpy(res.orientation)[2] - quat_to_rpy(res.filter_orientation)[2]
    assert math.remainder(dyaw - 0.3, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)
