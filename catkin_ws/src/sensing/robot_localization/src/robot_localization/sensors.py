"""Sensor front-end without ROS: turns pose / twist / IMU data into EKF measurements
according to each sensor's *_config, *_differential, *_relative, thresholds and two_d_mode.

Poses are (x, y, z, roll, pitch, yaw) with a 6x6 covariance; twists (vx, vy, vz, vroll,
vpitch, vyaw) with a 6x6 covariance; all in the world frame (poses) or the body frame
(twists, IMU vectors), already transformed by the caller.
"""
import math

import numpy as np
from course_runtime import geometry

from .ekf import Measurement, normalize_angle

TWO_D_VARIANCE = 1e-6
LARGE_COVARIANCE = 1e3
POSE_2D_ZEROED = (2, 3, 4)          # z, roll, pitch
TWIST_2D_ZEROED = (8, 9, 10)        # vz, vroll, vpitch
ACCEL_2D_ZEROED = (14,)             # az


class SensorConfig:
    """One input (odomN, poseN, twistN or imuN) with the original's per-sensor parameters."""

    def __init__(self, name, kind, topic, config, queue_size=1, differential=False,
                 relative=False, pose_rejection_threshold=float('inf'),
                 twist_rejection_threshold=float('inf'),
                 linear_acceleration_rejection_threshold=float('inf'),
                 remove_gravitational_acceleration=False):
        self.name, self.kind, self.topic = name, kind, topic
        self.config = [bool(c) for c in config]
        self.queue_size = queue_size
        self.differential = differential
        self.relative = relative and not differential
        self.pose_rejection_threshold = pose_rejection_threshold
        self.twist_rejection_threshold = twist_rejection_threshold
        self.linear_acceleration_rejection_threshold = linear_acceleration_rejection_threshold
        self.remove_gravitational_acceleration = remove_gravitational_acceleration
        # differential / relative state
        self.prev_pose = None
        self.prev_cov = None
        self.prev_time = None
        self.first_pose = None

    @property
    def pose_flags(self):
        return self.config[0:6]

    @property
    def twist_flags(self):
        return self.config[6:12]

    @property
    def accel_flags(self):
        return self.config[12:15]


def config_warnings(cfg):
    """Configuration problems of one sensor, in the original's words."""
    out = []
    if len(cfg.config) != 15:
        out.append('Configuration vector for %s_config should have 15 entries.' % cfg.name)
    if cfg.kind == 'imu':
        if any(cfg.config[0:3]):
            out.append('Warning: Some position entries in parameter %s_config are listed true, but '
                       'sensor_msgs/Imu contains no information about position' % cfg.name)
        if any(cfg.config[6:9]):
            out.append('Warning: Some linear velocity entries in parameter %s_config are listed '
                       'true, but an sensor_msgs/Imu contains no information about velocity'
                       % cfg.name)
    if not any(cfg.config):
        out.append('%s is listed as an input topic, but all update variables are false' % cfg.topic)
    return out


def covariance_warnings(topic, part, cov, flags, offset):
    """The original's per-variable covariance checks (only for fused variables)."""
    from .ekf import STATE_NAMES
    out = []
    for i, used in enumerate(flags):
        if not used:
            continue
        v = cov[i][i]
        name = STATE_NAMES[offset + i]
        if not math.isfinite(v):
            out.append('The covariance at position %d of the %s %s covariance is not finite; the '
                       'message is ignored.' % (i, topic, part))
        elif v < 0.0:
            out.append('The covariance at position %d, which corresponds to %s, of the %s %s '
                       'covariance was negative. Using its absolute value.' % (i, name, topic, part))
        elif v == 0.0:
            out.append('The covariance at position %d, which corresponds to %s, of the %s %s '
                       'covariance was zero. This will be replaced with a small value to maintain '
                       'filter stability, but should be corrected at the message origin node.'
                       % (i, name, topic, part))
        elif v > LARGE_COVARIANCE:
            out.append('The covariance at position %d, which corresponds to %s, of the %s %s '
                       'covariance the value is extremely large (%g), but the update vector for '
                       'that variable is set to true. This may be a sign of an error.'
                       % (i, name, topic, part, v))
    return out


def _select(values, cov, flags, offset, two_d, zeroed):
    idx = [offset + i for i, f in enumerate(flags) if f]
    sel = [i for i, f in enumerate(flags) if f]
    z = [values[i] for i in sel]
    c = np.asarray(cov, float)[np.ix_(sel, sel)] if sel else np.zeros((0, 0))
    if two_d:
        keep = [k for k, i in enumerate(idx) if i not in zeroed]
        idx = [idx[k] for k in keep]
        z = [z[k] for k in keep]
        c = c[np.ix_(keep, keep)]
        n0 = len(idx)
        idx = idx + list(zeroed)
        z = z + [0.0] * len(zeroed)
        c2 = np.zeros((len(idx), len(idx)))
        c2[:n0, :n0] = c
        for k in range(n0, len(idx)):
            c2[k, k] = TWO_D_VARIANCE
        c = c2
    return z, c, idx


def _rot(r, p, y):
    sr, cr, sp, cp, sy, cy = math.sin(r), math.cos(r), math.sin(p), math.cos(p), math.sin(y), math.cos(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _rpy(R):
    pitch = -math.asin(max(-1.0, min(1.0, R[2, 0])))
    roll = math.atan2(R[2, 1], R[2, 2])
    yaw = math.atan2(R[1, 0], R[0, 0])
    return roll, pitch, yaw


def relative_pose(first, pose):
    """pose expressed relative to first (first^-1 * pose)."""
    R0 = _rot(*first[3:6])
    R = _rot(*pose[3:6])
    t = R0.T @ (np.asarray(pose[0:3]) - np.asarray(first[0:3]))
    return tuple(t) + _rpy(R0.T @ R)


def pose_measurement(cfg, time, pose, cov, two_d=False):
    """Measurement for the pose part, or None (nothing to fuse / first differential sample)."""
    flags = list(cfg.pose_flags)
    if not any(flags) and not two_d:
        return None
    if cfg.differential:
        return _differential(cfg, time, pose, cov, two_d)
    if cfg.relative:
        if cfg.first_pose is None:
            cfg.first_pose = tuple(pose)
        pose = relative_pose(cfg.first_pose, pose)
    if not any(flags):
        return None
    z, c, idx = _select(pose, cov, flags, 0, two_d, POSE_2D_ZEROED)
    return Measurement(time, z, c, idx, cfg.pose_rejection_threshold, cfg.topic)


def _differential(cfg, time, pose, cov, two_d):
    """Pose deltas between consecutive messages, fused as body-frame velocities."""
    prev, prev_cov, prev_time = cfg.prev_pose, cfg.prev_cov, cfg.prev_time
    cfg.prev_pose, cfg.prev_cov, cfg.prev_time = tuple(pose), np.asarray(cov, float), time
    if prev is None or time <= prev_time:
        return None
    dt = time - prev_time
    delta = relative_pose(prev, pose)
    vel = [delta[0] / dt, delta[1] / dt, delta[2] / dt,
           normalize_angle(delta[3]) / dt, normalize_angle(delta[4]) / dt,
           normalize_angle(delta[5]) / dt]
    R = _rot(*prev[3:6]).T
    R6 = np.zeros((6, 6))
    R6[0:3, 0:3] = R
    R6[3:6, 3:6] = np.eye(3)
    vcov = R6 @ (prev_cov + np.asarray(cov, float)) @ R6.T / (dt * dt)
    flags = list(cfg.pose_flags)
    if not any(flags):
        return None
    z, c, idx = _select(vel, vcov, flags, 6, two_d, TWIST_2D_ZEROED)
    return Measurement(time, z, c, idx, cfg.pose_rejection_threshold, cfg.topic)


def twist_measurement(cfg, time, twist, cov, two_d=False):
    flags = list(cfg.twist_flags)
    if not any(flags):
        return None
    z, c, idx = _select(twist, cov, flags, 6, two_d, TWIST_2D_ZEROED)
    return Measurement(time, z, c, idx, cfg.twist_rejection_threshold, cfg.topic)


def accel_measurement(cfg, time, accel, cov, two_d=False):
    flags = list(cfg.accel_flags)
    if not any(flags):
        return None
    z, c, idx = _select(accel, cov, flags, 0, two_d, (2,))
    idx = [12 + i for i in idx]
    return Measurement(time, z, c, idx, cfg.linear_acceleration_rejection_threshold, cfg.topic)


def imu_orientation_measurement(cfg, time, rpy, cov3, two_d=False):
    """IMU orientation: only roll, pitch, yaw of the config are used."""
    flags = [False, False, False] + list(cfg.config[3:6])
    if not any(flags):
        return None
    cov6 = np.zeros((6, 6))
    cov6[3:6, 3:6] = cov3
    if cfg.differential:
        return _differential(cfg, time, (0.0, 0.0, 0.0) + tuple(rpy), cov6, two_d)
    pose = (0.0, 0.0, 0.0) + tuple(rpy)
    if cfg.relative:
        if cfg.first_pose is None:
            cfg.first_pose = pose
        pose = relative_pose(cfg.first_pose, pose)
    z, c, idx = _select(pose, cov6, flags, 0, two_d, POSE_2D_ZEROED)
    return Measurement(time, z, c, idx, cfg.pose_rejection_threshold, cfg.topic)


def imu_angular_measurement(cfg, time, omega, cov3, two_d=False):
    flags = [False, False, False] + list(cfg.config[9:12])
    if not any(flags):
        return None
    cov6 = np.zeros((6, 6))
    cov6[3:6, 3:6] = cov3
    z, c, idx = _select((0.0, 0.0, 0.0) + tuple(omega), cov6, flags, 6, two_d, TWIST_2D_ZEROED)
    return Measurement(time, z, c, idx, cfg.twist_rejection_threshold, cfg.topic)


def quaternion_to_rpy(q):
    """(w, x, y, z) -> (roll, pitch, yaw); the original's "not normalized" case is normalised."""
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


rpy_to_quaternion = geometry.quaternion_wxyz   # (w, x, y, z) of roll, pitch, yaw
