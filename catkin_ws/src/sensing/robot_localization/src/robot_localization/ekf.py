"""robot_localization's EKF: 15-D state, omnidirectional constant-acceleration model.

The filter itself is C++ (include/robot_localization/ekf.h, src/core/ekf.cpp; the node's
per-measurement cost is dominated by 15x15 matrix products, 0.15-0.25 ms in NumPy); this module
is its Python face for the node and the tests. No ROS imports. State order (STATE_NAMES): pose
in the world frame, velocities and accelerations in the body frame. Units: m, rad, s.
"""
import numpy as np

try:
    from robot_localization import _ekf_core as _core
except ImportError as _e:   # the catkin build puts _ekf_core.so into the devel space's package
    raise ImportError('robot_localization: the compiled EKF core robot_localization._ekf_core is not '
                      'built (%s): build the workspace (scripts/build.sh)' % _e)

STATE_SIZE = 15
X, Y, Z, ROLL, PITCH, YAW, VX, VY, VZ, VROLL, VPITCH, VYAW, AX, AY, AZ = range(STATE_SIZE)
STATE_NAMES = ('x', 'y', 'z', 'roll', 'pitch', 'yaw', 'x_vel', 'y_vel', 'z_vel', 'roll_vel',
               'pitch_vel', 'yaw_vel', 'x_accel', 'y_accel', 'z_accel')
ANGLES = (ROLL, PITCH, YAW)

DEFAULT_PROCESS_NOISE = np.diag([0.05, 0.05, 0.06, 0.03, 0.03, 0.06, 0.025, 0.025, 0.04,
                                 0.01, 0.01, 0.02, 0.01, 0.01, 0.015])
DEFAULT_INITIAL_COVARIANCE = np.eye(STATE_SIZE) * 1e-9
MIN_VARIANCE = _core.MIN_VARIANCE
NAN_ERROR = ('Critical Error, NaNs were detected in the output state of the filter. This was '
             'likely due to poorly conditioned process, noise, or sensor covariances.')
normalize_angle = _core.normalize_angle


class Measurement:
    """z (k,), covariance (k, k) and the state indices (k,) they measure; time in s."""
    __slots__ = ('time', 'z', 'covariance', 'indices', 'threshold', 'topic')

    def __init__(self, time, z, covariance, indices, threshold=float('inf'), topic=''):
        self.time = time
        self.z = np.asarray(z, dtype=float)
        self.covariance = np.asarray(covariance, dtype=float).reshape(len(self.z), len(self.z))
        self.indices = np.asarray(indices, dtype=np.int32)
        self.threshold = threshold
        self.topic = topic


class Ekf:
    """The compiled filter: `x` and `P` are NumPy views of its state and covariance (writable
    in place; assigning copies into the filter); `last_time` is None before the first
    measurement or prediction."""

    def __init__(self, process_noise=None, initial_covariance=None):
        self._f = _core.Ekf()
        self._f.Q = np.array(DEFAULT_PROCESS_NOISE if process_noise is None else process_noise, float)
        self._f.P0 = np.array(DEFAULT_INITIAL_COVARIANCE if initial_covariance is None
                              else initial_covariance, float)
        self.reset()

    def reset(self, state=None):
        if state is None:
            self._f.reset()
        else:
            self._f.reset(np.array(state, float))

    x = property(lambda self: self._f.x, lambda self, v: setattr(self._f, 'x', np.asarray(v, float)))
    P = property(lambda self: self._f.P, lambda self, v: setattr(self._f, 'P', np.asarray(v, float)))
    Q = property(lambda self: self._f.Q)
    P0 = property(lambda self: self._f.P0)
    initialized = property(lambda self: self._f.initialized,
                           lambda self, v: setattr(self._f, 'initialized', bool(v)))
    rejected = property(lambda self: self._f.rejected)
    nan_detected = property(lambda self: self._f.nan_detected,
                            lambda self, v: setattr(self._f, 'nan_detected', bool(v)))

    @property
    def last_time(self):
        return self._f.time if self._f.has_time else None

    @last_time.setter
    def last_time(self, t):
        self._f.has_time = t is not None
        self._f.time = 0.0 if t is None else float(t)

    def transfer(self, dt):
        """(F, J): the state transition matrix and its Jacobian for the current state."""
        return self._f.transfer(dt)

    def predict(self, time):
        """Project the state to `time` (s). No-op for dt <= 0."""
        self._f.predict(time)

    @staticmethod
    def sanitize_covariance(cov):
        """Negative variances -> absolute value, tiny ones -> MIN_VARIANCE (as the original)."""
        return _core.sanitize_covariance(np.asarray(cov, float))

    def process(self, m):
        """Filter one measurement: initialise from it, or predict to its time and correct.
        Returns True if it was fused (False: rejected by the Mahalanobis gate)."""
        return self._f.process(m.time, m.z, m.covariance, m.indices, m.threshold)

    def correct(self, m):
        """Kalman update with m (Joseph form; a diagonal covariance as sequential scalar
        updates, the same result as the batch update)."""
        return self._f.correct(m.z, m.covariance, m.indices, m.threshold)
