"""A synthetic 2-D drive for the EKF tests: ground truth, slipping wheel odometry, an IMU."""
import math
import random


def drive(duration=60.0, odom_rate=25.0, imu_rate=50.0, seed=7):
    """Returns (truth, events): truth(t) -> (x, y, yaw); events sorted by time:
    ('odom', t, (x, y, yaw, v, w)) wheel odometry (integrated with slip), ('imu', t, w_meas)."""
    rnd = random.Random(seed)
    dt = 0.005
    x = y = yaw = 0.0
    ox = oy = oyaw = 0.0
    truth = []
    events = []
    next_odom, next_imu = 0.0, 0.0
    t = 0.0
    slip_scale = 1.0
    n = int(round(duration / dt))
    for i in range(n + 1):
        t = i * dt
        v = 0.3 + 0.1 * math.sin(0.2 * t)
        w = 0.5 * math.sin(0.25 * t) + 0.2 * math.sin(0.9 * t)
        # wheel slip: the wheels over-report rotation (skid on turns) and occasionally spin
        if i % 200 == 0:
            slip_scale = 1.0 + rnd.uniform(0.05, 0.25)
        w_wheel = w * slip_scale + rnd.gauss(0, 0.02)
        v_wheel = v * (1.0 + 0.02) + rnd.gauss(0, 0.01)
        if t >= next_odom - 1e-9:
            events.append(('odom', t, (ox, oy, oyaw, v_wheel, w_wheel)))
            next_odom += 1.0 / odom_rate
        if t >= next_imu - 1e-9:
            events.append(('imu', t, w + 0.003 + rnd.gauss(0, 0.01)))
            next_imu += 1.0 / imu_rate
        truth.append((t, x, y, yaw))
        x += v * math.cos(yaw) * dt
        y += v * math.sin(yaw) * dt
        yaw += w * dt
        ox += v_wheel * math.cos(oyaw) * dt
        oy += v_wheel * math.sin(oyaw) * dt
        oyaw += w_wheel * dt
    events.sort(key=lambda e: (e[1], e[0]))
    return truth, events


def truth_at(truth, t, dt=0.005):
    return truth[min(len(truth) - 1, int(round(t / dt)))][1:]
