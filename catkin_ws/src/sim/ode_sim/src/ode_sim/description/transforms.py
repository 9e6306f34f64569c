"""Rigid transforms: a Pose is a position and a unit quaternion (x, y, z, w), as in ROS.

`a * b` composes (the pose of frame b given in frame a, expressed in a's parent);
`a.inverse()`; `a.apply(points)` maps points (N x 3) from the pose's frame to its parent.
"""
import math
from collections import namedtuple

import numpy as np
from course_runtime import geometry

_Quaternion = namedtuple('_Quaternion', 'x y z w')    # course_runtime.geometry reads fields


def quat_from_rpy(roll, pitch, yaw):
    """Quaternion (x, y, z, w) of fixed-axis roll about X, then pitch about Y, then yaw about Z
    (the URDF / SDF / tf convention)."""
    w, x, y, z = geometry.quaternion_wxyz(roll, pitch, yaw)
    return np.array([x, y, z, w])


def rpy_from_quat(q):
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    sinp = max(-1.0, min(1.0, 2 * (w * y - z * x)))
    pitch = math.asin(sinp)
    return np.array([roll, pitch, yaw_of(q)])


def quat_multiply(a, b):
    return np.array(qmul(a, b))


def quat_conjugate(q):
    return np.array([-q[0], -q[1], -q[2], q[3]])


def quat_to_matrix(q):
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def quat_from_matrix(m):
    m = np.asarray(m, dtype=float)
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s]
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        q = [0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s]
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        q = [(m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s]
    else:
        s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
        q = [(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s, (m[1, 0] - m[0, 1]) / s]
    q = np.array(q)
    return q / np.linalg.norm(q)


def quat_from_axis_angle(axis, angle):
    axis = np.asarray(axis, dtype=float)
    n = np.linalg.norm(axis)
    if n == 0:
        return np.array([0.0, 0.0, 0.0, 1.0])
    s = math.sin(angle / 2) / n
    return np.array([axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)])


# -- the same rotations on plain float tuples: per-step sensor maths (IMU, odometry, link
#    poses) without numpy's per-call overhead on 3- and 4-vectors --------------------------
def qmul(a, b):
    """quat_multiply on tuples: a * b -> (x, y, z, w)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def qnormalize(q):
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w)
    return (x / n, y / n, z / n, w / n) if n > 0 else (0.0, 0.0, 0.0, 1.0)


def qrotate(q, v):
    """quat_to_matrix(q) @ v on tuples."""
    x, y, z, w = q
    vx, vy, vz = v
    return ((1 - 2 * (y * y + z * z)) * vx + 2 * (x * y - z * w) * vy + 2 * (x * z + y * w) * vz,
            2 * (x * y + z * w) * vx + (1 - 2 * (x * x + z * z)) * vy + 2 * (y * z - x * w) * vz,
            2 * (x * z - y * w) * vx + 2 * (y * z + x * w) * vy + (1 - 2 * (x * x + y * y)) * vz)


def qrotate_inv(q, v):
    """quat_to_matrix(q).T @ v on tuples (a world vector in the frame q)."""
    x, y, z, w = q
    vx, vy, vz = v
    return ((1 - 2 * (y * y + z * z)) * vx + 2 * (x * y + z * w) * vy + 2 * (x * z - y * w) * vz,
            2 * (x * y - z * w) * vx + (1 - 2 * (x * x + z * z)) * vy + 2 * (y * z + x * w) * vz,
            2 * (x * z + y * w) * vx + 2 * (y * z - x * w) * vy + (1 - 2 * (x * x + y * y)) * vz)


def yaw_of(q):
    """rpy_from_quat(q)[2] of q = (x, y, z, w): course_runtime.geometry.yaw_of, the one
    implementation the course's packages share."""
    return geometry.yaw_of(_Quaternion(*q))


class Pose:
    __slots__ = ('p', 'q')

    def __init__(self, p=(0.0, 0.0, 0.0), q=(0.0, 0.0, 0.0, 1.0)):
        self.p = np.array(p, dtype=float)
        q = np.array(q, dtype=float)
        n = np.linalg.norm(q)
        self.q = q / n if n > 0 else np.array([0.0, 0.0, 0.0, 1.0])

    @classmethod
    def unit(cls, p, q):
        """A Pose of a position and an already unit quaternion (no normalisation)."""
        pose = cls.__new__(cls)
        pose.p = np.array(p, dtype=float)
        pose.q = np.array(q, dtype=float)
        return pose

    def tuples(self):
        """(p, q) as float tuples, for the tuple functions above."""
        p, q = self.p, self.q
        return ((float(p[0]), float(p[1]), float(p[2])),
                (float(q[0]), float(q[1]), float(q[2]), float(q[3])))

    @classmethod
    def from_xyz_rpy(cls, xyz=(0, 0, 0), rpy=(0, 0, 0)):
        return cls(xyz, quat_from_rpy(*rpy))

    @classmethod
    def from_matrix(cls, m):
        m = np.asarray(m, dtype=float)
        return cls(m[:3, 3], quat_from_matrix(m[:3, :3]))

    @classmethod
    def parse(cls, text):
        """'x y z roll pitch yaw' (SDF <pose>); missing/empty text is the identity."""
        vals = [float(v) for v in (text or '').split()]
        if not vals:
            return cls()
        if len(vals) != 6:
            raise ValueError('pose needs 6 numbers "x y z roll pitch yaw", got %r' % text)
        return cls.from_xyz_rpy(vals[:3], vals[3:])

    def rpy(self):
        return rpy_from_quat(self.q)

    def rotation(self):
        return quat_to_matrix(self.q)

    def matrix(self):
        m = np.eye(4)
        m[:3, :3] = quat_to_matrix(self.q)
        m[:3, 3] = self.p
        return m

    def __mul__(self, other):
        return Pose(self.p + quat_to_matrix(self.q) @ other.p, quat_multiply(self.q, other.q))

    def inverse(self):
        qi = quat_conjugate(self.q)
        return Pose(-(quat_to_matrix(qi) @ self.p), qi)

    def apply(self, points):
        """Points (3,) or (N, 3) from this frame into the parent frame."""
        pts = np.asarray(points, dtype=float)
        return pts @ quat_to_matrix(self.q).T + self.p

    def rotate(self, vectors):
        return np.asarray(vectors, dtype=float) @ quat_to_matrix(self.q).T

    def copy(self):
        return Pose(self.p.copy(), self.q.copy())

    def __repr__(self):
        return 'Pose(p=%s, rpy=%s)' % (np.round(self.p, 4).tolist(), np.round(self.rpy(), 4).tolist())
