"""Odometry motion models (amcl's AMCLOdom): 'diff', 'omni', 'diff-corrected',
'omni-corrected', sampled for all particles at once.

As the original, the uncorrected models pass the variance expression where a standard
deviation belongs (kept for compatibility: tuned alphas depend on it); the *-corrected models
take its square root (Probabilistic Robotics, table 5.6)."""
import numpy as np

ODOM_MODELS = ('diff', 'omni', 'diff-corrected', 'omni-corrected')


def normalize(a):
    """Angle(s) to [-pi, pi)."""
    return (np.asarray(a) + np.pi) % (2.0 * np.pi) - np.pi


def angle_diff(a, b):
    """Smallest signed difference a - b."""
    return normalize(np.asarray(a) - np.asarray(b))


class OdomModel:
    def __init__(self, model_type='diff', alpha1=0.2, alpha2=0.2, alpha3=0.2, alpha4=0.2,
                 alpha5=0.2, rng=None):
        if model_type not in ODOM_MODELS:
            raise ValueError('unknown odom_model_type "%s" (one of %s)' % (model_type, ', '.join(ODOM_MODELS)))
        self.model_type = model_type
        self.alpha1, self.alpha2, self.alpha3, self.alpha4, self.alpha5 = alpha1, alpha2, alpha3, alpha4, alpha5
        self.rng = rng if rng is not None else np.random.default_rng()

    def _gauss(self, sigma, n):
        return self.rng.normal(0.0, 1.0, n) * sigma

    def sample(self, poses, pose, delta):
        """Move particles (N, 3) in place by the odometry delta. pose: the new odometric pose
        (x, y, yaw), delta = pose - old pose (x, y and the angle difference)."""
        n = poses.shape[0]
        dx, dy, dth = float(delta[0]), float(delta[1]), float(delta[2])
        old_theta = float(pose[2]) - dth
        corrected = self.model_type.endswith('-corrected')
        fix = np.sqrt if corrected else (lambda v: v)
        trans = np.hypot(dx, dy)
        if self.model_type.startswith('omni'):
            rot = dth
            trans_sd = fix(self.alpha3 * trans ** 2 + self.alpha1 * rot ** 2)
            rot_sd = fix(self.alpha4 * rot ** 2 + self.alpha2 * trans ** 2)
            strafe_sd = fix(self.alpha1 * rot ** 2 + self.alpha5 * trans ** 2)
            bearing = float(angle_diff(np.arctan2(dy, dx), old_theta)) + poses[:, 2]
            cs, sn = np.cos(bearing), np.sin(bearing)
            trans_hat = trans + self._gauss(trans_sd, n)
            rot_hat = rot + self._gauss(rot_sd, n)
            strafe_hat = self._gauss(strafe_sd, n)
            poses[:, 0] += trans_hat * cs + strafe_hat * sn
            poses[:, 1] += trans_hat * sn - strafe_hat * cs
            poses[:, 2] += rot_hat
        else:
            rot1 = 0.0 if trans < 0.01 else float(angle_diff(np.arctan2(dy, dx), old_theta))
            rot2 = float(angle_diff(dth, rot1))
            # driving backwards is as cheap as forwards: noise from the smaller of the two turns
            rot1_noise = min(abs(float(angle_diff(rot1, 0.0))), abs(float(angle_diff(rot1, np.pi))))
            rot2_noise = min(abs(float(angle_diff(rot2, 0.0))), abs(float(angle_diff(rot2, np.pi))))
            rot1_hat = angle_diff(rot1, self._gauss(fix(self.alpha1 * rot1_noise ** 2 + self.alpha2 * trans ** 2), n))
            trans_hat = trans - self._gauss(fix(self.alpha3 * trans ** 2 + self.alpha4 * rot1_noise ** 2
                                                + self.alpha4 * rot2_noise ** 2), n)
            rot2_hat = angle_diff(rot2, self._gauss(fix(self.alpha1 * rot2_noise ** 2 + self.alpha2 * trans ** 2), n))
            poses[:, 0] += trans_hat * np.cos(poses[:, 2] + rot1_hat)
            poses[:, 1] += trans_hat * np.sin(poses[:, 2] + rot1_hat)
            poses[:, 2] += rot1_hat + rot2_hat
        poses[:, 2] = normalize(poses[:, 2])
        return poses
