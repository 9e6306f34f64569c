"""gmapping's odometry motion model (MotionModel::drawFromMotion) and pose algebra."""
import numpy as np


def normalize_angle(a):
    return (np.asarray(a) + np.pi) % (2.0 * np.pi) - np.pi


def absolute_difference(p1, p2):
    """Pose p1 expressed in the frame of pose p2 (gmapping's absoluteDifference)."""
    dx, dy = p1[0] - p2[0], p1[1] - p2[1]
    c, s = np.cos(p2[2]), np.sin(p2[2])
    return np.array([c * dx + s * dy, -s * dx + c * dy, float(normalize_angle(p1[2] - p2[2]))])


def absolute_sum(poses, d):
    """Compose poses (n, 3) with per-pose relative motions d (n, 3) (gmapping's absoluteSum)."""
    c, s = np.cos(poses[:, 2]), np.sin(poses[:, 2])
    out = np.empty_like(poses)
    out[:, 0] = poses[:, 0] + c * d[:, 0] - s * d[:, 1]
    out[:, 1] = poses[:, 1] + s * d[:, 0] + c * d[:, 1]
    out[:, 2] = normalize_angle(poses[:, 2] + d[:, 2])
    return out


def draw_from_motion(poses, old_odom, new_odom, srr, srt, str_, stt, rng):
    """Sample new poses (n, 3) for particles at `poses` given the odometry step old -> new.
    Noise: trans sigma = srr*|trans| + str*|rot| (+ 0.3*srr cross term), rot sigma = stt*|rot| +
    srt*|trans|, as gmapping's drawFromMotion."""
    poses = np.asarray(poses, dtype=np.float64)
    n = poses.shape[0]
    delta = absolute_difference(np.asarray(new_odom, float), np.asarray(old_odom, float))
    sxy = 0.3 * srr
    ax, ay, at = abs(delta[0]), abs(delta[1]), abs(delta[2])
    sig = np.array([srr * ax + str_ * at + sxy * ay,
                    srr * ay + str_ * at + sxy * ax,
                    stt * at + srt * np.hypot(delta[0], delta[1])])
    noisy = delta[None, :] + rng.standard_normal((n, 3)) * sig[None, :]
    return absolute_sum(poses, noisy)
