"""A simulated IMU for the unit tests: true orientation, gyro and accelerometer with noise."""
import math
import random

from imu_filter_madgwick.filter import quat_mul, quat_normalize, rotate, quat_conj

G = 9.80665


def body_vector(q, v):
    """World vector v expressed in the body frame of orientation q."""
    return rotate(quat_conj(q), v)


def tilt_error_deg(q_est, q_true):
    """Angle between the estimated and the true 'up' direction seen from the body."""
    a = body_vector(q_est, (0, 0, 1))
    b = body_vector(q_true, (0, 0, 1))
    d = max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b))))
    return math.degrees(math.acos(d))


def angle_deg(q1, q2):
    d = abs(sum(a * b for a, b in zip(q1, q2)))
    return math.degrees(2 * math.acos(min(1.0, d)))


def simulate(q0, omega_fn, duration, rate=100.0, gyro_noise=0.0, accel_noise=0.0, seed=1,
             mag_world=None, up=(0.0, 0.0, 1.0)):
    """Yields (t, q_true, gyro, accel, mag) samples; omega_fn(t) -> body rates (rad/s)."""
    rnd = random.Random(seed)
    dt = 1.0 / rate
    q = q0
    n = int(round(duration * rate))
    for i in range(n + 1):
        t = i * dt
        w = omega_fn(t)
        g = body_vector(q, (up[0] * G, up[1] * G, up[2] * G))
        accel = tuple(c + rnd.gauss(0, accel_noise) for c in g)
        gyro = tuple(c + rnd.gauss(0, gyro_noise) for c in w)
        mag = body_vector(q, mag_world) if mag_world else None
        yield t, q, gyro, accel, mag
        # exact integration of constant body rate over dt
        ang = math.sqrt(sum(c * c for c in w)) * dt
        if ang > 0:
            axis = [c * dt / ang for c in w]
            s = math.sin(ang / 2)
            q = quat_normalize(quat_mul(q, (math.cos(ang / 2), axis[0] * s, axis[1] * s, axis[2] * s)))
