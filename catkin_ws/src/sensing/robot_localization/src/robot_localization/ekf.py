"""robot_localization's EKF core: 15-D state, omnidirectional constant-acceleration model.

No ROS imports. State order (STATE_NAMES): pose in the world frame, velocities and
accelerations in the body frame. Units: m, rad, s.
"""
import math

import numpy as np

STATE_SIZE = 15
X, Y, Z, ROLL, PITCH, YAW, VX, VY, VZ, VROLL, VPITCH, VYAW, AX, AY, AZ = range(STATE_SIZE)
STATE_NAMES = ('x', 'y', 'z', 'roll', 'pitch', 'yaw', 'x_vel', 'y_vel', 'z_vel', 'roll_vel',
               'pitch_vel', 'yaw_vel', 'x_accel', 'y_accel', 'z_accel')
ANGLES = (ROLL, PITCH, YAW)

DEFAULT_PROCESS_NOISE = np.diag([0.05, 0.05, 0.06, 0.03, 0.03, 0.06, 0.025, 0.025, 0.04,
                                 0.01, 0.01, 0.02, 0.01, 0.01, 0.015])
DEFAULT_INITIAL_COVARIANCE = np.eye(STATE_SIZE) * 1e-9
MIN_VARIANCE = 1e-9
NAN_ERROR = ('Critical Error, NaNs were detected in the output state of the filter. This was '
             'likely due to poorly conditioned process, noise, or sensor covariances.')


def normalize_angle(a):
    return (a + math.pi) % (2.0 * math.pi) - math.pi


class Measurement:
    """z (k,), covariance (k, k) and the state indices (k,) they measure; time in s."""
    __slots__ = ('time', 'z', 'covariance', 'indices', 'threshold', 'topic')

    def __init__(self, time, z, covariance, indices, threshold=float('inf'), topic=''):
        self.time = time
        self.z = np.asarray(z, dtype=float)
        self.covariance = np.asarray(covariance, dtype=float)
        self.indices = np.asarray(indices, dtype=int)
        self.threshold = threshold
        self.topic = topic


class Ekf:
    def __init__(self, process_noise=None, initial_covariance=None):
        self.Q = np.array(DEFAULT_PROCESS_NOISE if process_noise is None else process_noise, float)
        self.P0 = np.array(DEFAULT_INITIAL_COVARIANCE if initial_covariance is None
                           else initial_covariance, float)
        self.reset()

    def reset(self, state=None):
        self.x = np.zeros(STATE_SIZE) if state is None else np.array(state, float)
        self.P = self.P0.copy()
        self.initialized = False
        self.last_time = None
        self.rejected = 0
        self.nan_detected = False

    # ---- prediction -------------------------------------------------------------------------
    def transfer(self, dt):
        """(F, J): the state transition matrix and its Jacobian for the current state."""
        x = self.x
        sr, cr = math.sin(x[ROLL]), math.cos(x[ROLL])
        sp, cp = math.sin(x[PITCH]), math.cos(x[PITCH])
        sy, cy = math.sin(x[YAW]), math.cos(x[YAW])
        cp = cp if abs(cp) > 1e-9 else math.copysign(1e-9, cp)
        tp, secp = sp / cp, 1.0 / cp
        R = np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                      [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                      [-sp, cp * sr, cp * cr]])
        F = np.eye(STATE_SIZE)
        F[0:3, 6:9] = R * dt
        F[0:3, 12:15] = R * (0.5 * dt * dt)
        F[ROLL, VROLL] = dt
        F[ROLL, VPITCH] = sr * tp * dt
        F[ROLL, VYAW] = cr * tp * dt
        F[PITCH, VPITCH] = cr * dt
        F[PITCH, VYAW] = -sr * dt
        F[YAW, VPITCH] = sr * secp * dt
        F[YAW, VYAW] = cr * secp * dt
        F[6:9, 12:15] = np.eye(3) * dt
        # Jacobian: F plus the derivatives of the rotation-dependent terms by roll, pitch, yaw
        d = x[6:9] * dt + 0.5 * x[12:15] * dt * dt
        dR_dr = np.array([[0.0, cy * sp * cr + sy * sr, -cy * sp * sr + sy * cr],
                          [0.0, sy * sp * cr - cy * sr, -sy * sp * sr - cy * cr],
                          [0.0, cp * cr, -cp * sr]])
        dR_dp = np.array([[-cy * sp, cy * cp * sr, cy * cp * cr],
                          [-sy * sp, sy * cp * sr, sy * cp * cr],
                          [-cp, -sp * sr, -sp * cr]])
        dR_dy = np.array([[-sy * cp, -sy * sp * sr - cy * cr, -sy * sp * cr + cy * sr],
                          [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                          [0.0, 0.0, 0.0]])
        J = F.copy()
        J[0:3, ROLL] += dR_dr @ d
        J[0:3, PITCH] += dR_dp @ d
        J[0:3, YAW] += dR_dy @ d
        vp, vy = x[VPITCH], x[VYAW]
        J[ROLL, ROLL] += (cr * tp * vp - sr * tp * vy) * dt
        J[ROLL, PITCH] += (sr * secp * secp * vp + cr * secp * secp * vy) * dt
        J[PITCH, ROLL] += (-sr * vp - cr * vy) * dt
        J[YAW, ROLL] += (cr * secp * vp - sr * secp * vy) * dt
        J[YAW, PITCH] += (sr * vp + cr * vy) * tp * secp * dt
        return F, J

    def predict(self, time):
        """Project the state to `time` (s). No-op for dt <= 0."""
        if self.last_time is None:
            self.last_time = time
            return
        dt = time - self.last_time
        if dt <= 0.0:
            return
        F, J = self.transfer(dt)
        self.x = F @ self.x
        for i in ANGLES:
            self.x[i] = normalize_angle(self.x[i])
        self.P = J @ self.P @ J.T + self.Q * dt
        self.last_time = time

    # ---- correction -------------------------------------------------------------------------
    @staticmethod
    def sanitize_covariance(cov):
        """Negative variances -> absolute value, tiny ones -> MIN_VARIANCE (as the original)."""
        cov = np.array(cov, float)
        d = np.abs(np.diagonal(cov))
        np.fill_diagonal(cov, np.maximum(d, MIN_VARIANCE))
        return cov

    def process(self, m):
        """Filter one measurement: initialise from it, or predict to its time and correct.
        Returns True if it was fused (False: rejected by the Mahalanobis gate)."""
        if not self.initialized:
            idx = m.indices
            self.x[idx] = m.z
            cov = self.sanitize_covariance(m.covariance)
            self.P[np.ix_(idx, idx)] = cov
            self.initialized = True
            self.last_time = m.time
            return True
        self.predict(m.time)
        return self.correct(m)

    def correct(self, m):
        """Kalman update with m. A diagonal measurement covariance (the usual case) is fused as
        sequential scalar updates, equal to the batch update but free of LAPACK calls (which
        cost milliseconds on a loaded machine); the Mahalanobis distance of the whole vector is
        accumulated on the way (the chain rule of the Gaussian likelihood)."""
        idx = m.indices
        R = self.sanitize_covariance(m.covariance)
        if np.count_nonzero(R - np.diag(np.diagonal(R))) == 0:
            return self._correct_sequential(m, idx, np.diagonal(R))
        return self._correct_batch(m, idx, R)

    def _commit(self, x, P):
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(P))):
            self.nan_detected = True
            return False
        for i in ANGLES:
            x[i] = normalize_angle(x[i])
        self.x, self.P = x, P
        return True

    def _correct_sequential(self, m, idx, r):
        x = self.x.copy()
        P = self.P.copy()
        sq = 0.0
        z = m.z
        for k in range(len(idx)):
            i = idx[k]
            nu = z[k] - x[i]
            if i == ROLL or i == PITCH or i == YAW:
                nu = normalize_angle(nu)
            Pi = P[:, i].copy()
            S = Pi[i] + r[k]
            if not S > 0.0:
                return False
            sq += nu * nu / S
            K = Pi / S
            x += K * nu
            # Joseph form for a scalar measurement, (I - K h) P (I - K h)^T + K r K^T,
            # reduces to P - Pi Pi^T / S; symmetry is restored below
            P -= Pi[:, None] * K[None, :]
        if math.isfinite(m.threshold) and sq >= m.threshold * m.threshold:
            self.rejected += 1
            return False
        P = 0.5 * (P + P.T)
        return self._commit(x, P)

    def _correct_batch(self, m, idx, R):
        innovation = m.z - self.x[idx]
        for k, i in enumerate(idx):
            if i in ANGLES:
                innovation[k] = normalize_angle(innovation[k])
        Pxh = self.P[:, idx]                      # P H^T
        S = Pxh[idx, :] + R                       # H P H^T + R
        try:
            S_inv = np.linalg.inv(S)
        except np.linalg.LinAlgError:
            return False
        if math.isfinite(m.threshold):
            sq = float(innovation @ S_inv @ innovation)
            if sq >= m.threshold * m.threshold:
                self.rejected += 1
                return False
        K = Pxh @ S_inv
        x = self.x + K @ innovation
        # Joseph form: (I - KH) P (I - KH)^T + K R K^T
        IKH = np.eye(STATE_SIZE)
        IKH[:, idx] -= K
        P = IKH @ self.P @ IKH.T + K @ R @ K.T
        return self._commit(x, P)
