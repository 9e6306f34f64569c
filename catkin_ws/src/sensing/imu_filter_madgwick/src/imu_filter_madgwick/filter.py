"""Madgwick's gradient-descent orientation filter (IMU and MARG variants), no ROS imports.

Quaternions are tuples (w, x, y, z) giving the body -> world rotation (the ROS orientation
convention). Angular rates in rad/s, accelerations in any unit (normalised), dt in s.
Plain float arithmetic: a handful of scalars per sample is faster in Python than NumPy.
"""
import math

from course_runtime import geometry

WORLD_FRAMES = ('enu', 'ned', 'nwu')

FREE_FALL_WARNING = 'The IMU seems to be in free fall, cannot determine gravity direction!'
FREE_FALL_MAG_WARNING = ('The IMU seems to be in free fall or close to magnetic north pole, '
                         'cannot determine gravity direction!')


class FreeFall(ValueError):
    """The sample gives no usable gravity direction (zero, NaN, or mag parallel to gravity)."""


def quat_mul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


def quat_conj(q):
    return (q[0], -q[1], -q[2], -q[3])


def quat_normalize(q):
    n = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    return (q[0] / n, q[1] / n, q[2] / n, q[3] / n)


def rotate(q, v):
    """v rotated by q (body -> world)."""
    return quat_mul(quat_mul(q, (0.0, v[0], v[1], v[2])), quat_conj(q))[1:]


def quat_from_rows(r):
    """Quaternion of the rotation matrix r (3 rows), Shepperd's method."""
    (m00, m01, m02), (m10, m11, m12), (m20, m21, m22) = r
    tr = m00 + m11 + m22
    if tr > 0.0:
        s = 2.0 * math.sqrt(tr + 1.0)
        q = (0.25 * s, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s)
    elif m00 > m11 and m00 > m22:
        s = 2.0 * math.sqrt(1.0 + m00 - m11 - m22)
        q = ((m21 - m12) / s, 0.25 * s, (m01 + m10) / s, (m02 + m20) / s)
    elif m11 > m22:
        s = 2.0 * math.sqrt(1.0 + m11 - m00 - m22)
        q = ((m02 - m20) / s, (m01 + m10) / s, 0.25 * s, (m12 + m21) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m22 - m00 - m11)
        q = ((m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, 0.25 * s)
    return quat_normalize(q)


def quat_to_rpy(q):
    w, x, y, z = q
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    sp = max(-1.0, min(1.0, 2.0 * (w * y - z * x)))
    pitch = math.asin(sp)
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


quat_from_rpy = geometry.quaternion_wxyz      # (w, x, y, z) of roll, pitch, yaw


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _norm(v):
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


def orientation_from_measurement(accel, mag=None, world_frame='enu'):
    """Stateless orientation: accel points up; mag (or a vector orthogonal-ish to accel) fixes yaw.

    Raises FreeFall when no direction can be found (as the original skips the sample)."""
    ax, ay, az = accel
    if mag is None:
        if abs(ax) > 0.1 or abs(ay) > 0.1:
            field = (ay, ax, 0.0)
        elif abs(az) > 0.1:
            field = (0.0, az, ay)
        else:
            raise FreeFall(FREE_FALL_WARNING)
    else:
        field = mag
    east = _cross(field, accel)
    ne = _norm(east)
    if not ne >= 1e-7:          # also catches NaN
        raise FreeFall(FREE_FALL_WARNING if mag is None else FREE_FALL_MAG_WARNING)
    north = _cross(accel, east)
    nn, na = _norm(north), _norm(accel)
    e = (east[0] / ne, east[1] / ne, east[2] / ne)
    n = (north[0] / nn, north[1] / nn, north[2] / nn)
    u = (ax / na, ay / na, az / na)
    # rows of body->world: the world axes expressed in the body frame
    if world_frame == 'enu':
        rows = (e, n, u)
    elif world_frame == 'nwu':
        rows = (n, (-e[0], -e[1], -e[2]), u)
    else:   # ned
        rows = (n, e, (-u[0], -u[1], -u[2]))
    return quat_from_rows(rows)


def _grad(q, v, meas, s):
    """Add J(q)^T (R(q)^T v - meas) to s (list of 4): one gradient term of Madgwick's objective."""
    q0, q1, q2, q3 = q
    v0, v1, v2 = v
    u0 = (1 - 2 * (q2 * q2 + q3 * q3)) * v0 + 2 * (q1 * q2 + q0 * q3) * v1 + 2 * (q1 * q3 - q0 * q2) * v2
    u1 = 2 * (q1 * q2 - q0 * q3) * v0 + (1 - 2 * (q1 * q1 + q3 * q3)) * v1 + 2 * (q2 * q3 + q0 * q1) * v2
    u2 = 2 * (q1 * q3 + q0 * q2) * v0 + 2 * (q2 * q3 - q0 * q1) * v1 + (1 - 2 * (q1 * q1 + q2 * q2)) * v2
    f0, f1, f2 = u0 - meas[0], u1 - meas[1], u2 - meas[2]
    s[0] += ((2 * q3 * v1 - 2 * q2 * v2) * f0 + (-2 * q3 * v0 + 2 * q1 * v2) * f1
             + (2 * q2 * v0 - 2 * q1 * v1) * f2)
    s[1] += ((2 * q2 * v1 + 2 * q3 * v2) * f0 + (2 * q2 * v0 - 4 * q1 * v1 + 2 * q0 * v2) * f1
             + (2 * q3 * v0 - 2 * q0 * v1 - 4 * q1 * v2) * f2)
    s[2] += ((-4 * q2 * v0 + 2 * q1 * v1 - 2 * q0 * v2) * f0 + (2 * q1 * v0 + 2 * q3 * v2) * f1
             + (2 * q0 * v0 + 2 * q3 * v1 - 4 * q2 * v2) * f2)
    s[3] += ((-4 * q3 * v0 + 2 * q0 * v1 + 2 * q1 * v2) * f0
             + (-2 * q0 * v0 - 4 * q3 * v1 + 2 * q2 * v2) * f1 + (2 * q1 * v0 + 2 * q2 * v1) * f2)


class MadgwickFilter:
    """State: orientation q (body -> world) and gyro bias (MARG variant, zeta > 0)."""

    def __init__(self, gain=0.1, zeta=0.0, world_frame='enu'):
        if world_frame not in WORLD_FRAMES:
            raise ValueError("world_frame must be one of 'enu', 'ned', 'nwu', got %r" % (world_frame,))
        self.gain = gain
        self.zeta = zeta
        self.world_frame = world_frame
        self._g_ref = (0.0, 0.0, -1.0) if world_frame == 'ned' else (0.0, 0.0, 1.0)
        self.q = (1.0, 0.0, 0.0, 0.0)
        self.bias = (0.0, 0.0, 0.0)

    def set_orientation(self, q):
        self.q = quat_normalize(q)
        self.bias = (0.0, 0.0, 0.0)

    def update_imu(self, gyro, accel, dt):
        """One IMU (no magnetometer) step. Zero accel -> gyro-only integration."""
        q = self.q
        gx, gy, gz = gyro
        d = quat_mul(q, (0.0, gx, gy, gz))
        dw, dx, dy, dz = 0.5 * d[0], 0.5 * d[1], 0.5 * d[2], 0.5 * d[3]
        ax, ay, az = accel
        if not (ax == 0.0 and ay == 0.0 and az == 0.0):
            n = math.sqrt(ax * ax + ay * ay + az * az)
            s = [0.0, 0.0, 0.0, 0.0]
            _grad(q, self._g_ref, (ax / n, ay / n, az / n), s)
            ns = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + s[3] * s[3])
            if ns > 0.0:
                b = self.gain / ns
                dw -= b * s[0]
                dx -= b * s[1]
                dy -= b * s[2]
                dz -= b * s[3]
        self.q = quat_normalize((q[0] + dw * dt, q[1] + dx * dt, q[2] + dy * dt, q[3] + dz * dt))
        return self.q

    def update_marg(self, gyro, accel, mag, dt):
        """One MARG step; non-finite mag falls back to the IMU variant, zero accel to gyro only."""
        if not all(math.isfinite(c) for c in mag) or mag == (0.0, 0.0, 0.0):
            return self.update_imu(gyro, accel, dt)
        ax, ay, az = accel
        if ax == 0.0 and ay == 0.0 and az == 0.0:
            return self.update_imu(gyro, accel, dt)
        q = self.q
        na, nm = _norm(accel), _norm(mag)
        a = (ax / na, ay / na, az / na)
        m = (mag[0] / nm, mag[1] / nm, mag[2] / nm)
        h = rotate(q, m)
        hxy = math.hypot(h[0], h[1])
        b = (0.0, hxy, h[2]) if self.world_frame == 'enu' else (hxy, 0.0, h[2])
        s = [0.0, 0.0, 0.0, 0.0]
        _grad(q, self._g_ref, a, s)
        _grad(q, b, m, s)
        ns = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + s[3] * s[3])
        gx, gy, gz = gyro
        if ns > 0.0:
            sn = (s[0] / ns, s[1] / ns, s[2] / ns, s[3] / ns)
            err = quat_mul(quat_conj(q), sn)
            bx, by, bz = self.bias
            k = 2.0 * dt * self.zeta
            self.bias = (bx + err[1] * k, by + err[2] * k, bz + err[3] * k)
            gx, gy, gz = gx - self.bias[0], gy - self.bias[1], gz - self.bias[2]
        else:
            sn = (0.0, 0.0, 0.0, 0.0)
        d = quat_mul(q, (0.0, gx, gy, gz))
        g = self.gain
        self.q = quat_normalize(tuple(q[i] + (0.5 * d[i] - g * sn[i]) * dt for i in range(4)))
        return self.q


def valid_vector(v):
    return all(math.isfinite(c) for c in v)
