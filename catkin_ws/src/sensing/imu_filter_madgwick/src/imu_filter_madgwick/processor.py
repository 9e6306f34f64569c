"""Per-sample logic of imu_filter_node without ROS: initialisation, dt, stateless mode,
gravity removal, yaw offset and covariance. Warnings are returned as (key, text) so the node
can throttle them; the filter state is never touched by a rejected sample."""
import math

from .filter import (MadgwickFilter, FreeFall, orientation_from_measurement, quat_from_rpy,
                     quat_mul, quat_conj, rotate, valid_vector)

GRAVITY = 9.80665
ZERO_STAMP_WARNING = ('The IMU message time stamp is zero, and the parameter constant_dt is not '
                      'set! The filter will not update the orientation.')
NON_FINITE_WARNING = ('IMU message with a non-finite angular_velocity or linear_acceleration '
                      '(NaN/inf); sample skipped, filter state kept.')


class Params:
    """The node's parameters with the original's defaults."""

    def __init__(self, **kw):
        self.gain = 0.1
        self.zeta = 0.0
        self.mag_bias = (0.0, 0.0, 0.0)
        self.orientation_stddev = 0.0
        self.world_frame = 'enu'
        self.use_mag = True
        self.fixed_frame = 'odom'
        self.publish_tf = True
        self.reverse_tf = False
        self.constant_dt = 0.0
        self.publish_debug_topics = False
        self.stateless = False
        self.remove_gravity_vector = False
        self.yaw_offset = 0.0
        self.declination = 0.0
        self.time_jump_threshold = 0.0
        for k, v in kw.items():
            if not hasattr(self, k):
                raise AttributeError('unknown parameter %s' % k)
            setattr(self, k, v)


class Result:
    __slots__ = ('orientation', 'linear_acceleration', 'covariance', 'filter_orientation')

    def __init__(self, orientation, linear_acceleration, covariance, filter_orientation):
        self.orientation = orientation                  # published (yaw offset applied)
        self.linear_acceleration = linear_acceleration
        self.covariance = covariance                    # 9 floats, row-major
        self.filter_orientation = filter_orientation    # for TF (no yaw offset)


class ImuProcessor:
    def __init__(self, params):
        self.p = params
        self.filter = MadgwickFilter(params.gain, params.zeta, params.world_frame)
        self.initialized = False
        self.last_time = None
        self.warnings = []
        var = params.orientation_stddev ** 2
        self.covariance = (var, 0.0, 0.0, 0.0, var, 0.0, 0.0, 0.0, var)
        offset = params.yaw_offset - params.declination
        self._yaw_q = quat_from_rpy(0.0, 0.0, offset) if offset != 0.0 else None

    def reset(self):
        self.initialized = False
        self.last_time = None
        self.filter.set_orientation((1.0, 0.0, 0.0, 0.0))

    def _warn(self, key, text):
        self.warnings.append((key, text))

    def process(self, stamp, gyro, accel, mag=None):
        """stamp: seconds (0.0 = unset); mag already in the unit of the message (bias removed
        here). Returns a Result or None when the sample is skipped."""
        if not (valid_vector(gyro) and valid_vector(accel)):
            self._warn('nonfinite', NON_FINITE_WARNING)
            return None
        if mag is not None:
            b = self.p.mag_bias
            mag = (mag[0] - b[0], mag[1] - b[1], mag[2] - b[2])
            if not valid_vector(mag):
                if not self.initialized or self.p.stateless:
                    return None
                mag = None
        if self.p.stateless or not self.initialized:
            try:
                q = orientation_from_measurement(accel, mag, self.p.world_frame)
            except FreeFall as e:
                self._warn('freefall', str(e))
                return None
            self.filter.set_orientation(q)
            if not self.initialized:
                self.initialized = True
                self.last_time = stamp
                self._warn('first', 'First pair of IMU and magnetometer messages received.'
                           if mag is not None else 'First IMU message received.')
        else:
            if self.p.constant_dt > 0.0:
                dt = self.p.constant_dt
            elif stamp == 0.0:
                self._warn('zerostamp', ZERO_STAMP_WARNING)
                dt = 0.0
            else:
                dt = stamp - self.last_time if self.last_time else 0.0
            self.last_time = stamp
            if mag is not None:
                self.filter.update_marg(gyro, accel, mag, dt)
            else:
                self.filter.update_imu(gyro, accel, dt)
        return self._result(accel)

    def _result(self, accel):
        q = self.filter.q
        lin = accel
        if self.p.remove_gravity_vector:
            # gravity in the body frame = R^T * g_up
            g = rotate(quat_conj(q), (0.0, 0.0, -GRAVITY if self.p.world_frame == 'ned' else GRAVITY))
            lin = (accel[0] - g[0], accel[1] - g[1], accel[2] - g[2])
        out = quat_mul(self._yaw_q, q) if self._yaw_q is not None else q
        return Result(out, lin, self.covariance, q)


def check_time_jump(last_now, now, threshold):
    """True when ROS time went back by more than threshold seconds."""
    return last_now is not None and now < last_now - threshold and not math.isclose(now, last_now)
