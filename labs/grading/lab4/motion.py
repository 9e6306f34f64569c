"""Lab 4's motion on sim time: the robot's track metrics and the scene objects it displaced (no rospy)."""
import math

PUSH_TOL = 0.03           # m a scene object may move
TURN_TOL = 0.1            # rad a scene object may turn


def _yaw(q):
    x, y, z, w = q
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def _tilt(q):
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    return max(abs(roll), abs(pitch))


def motion(samples):
    """Metrics of a robot track [(t, x, y, z, qx, qy, qz, qw)] (t: sim time)."""
    if len(samples) < 2:
        return None
    x0, y0 = samples[0][1], samples[0][2]
    path = reach = turned = 0.0
    tilt = 0.0
    prev = samples[0]
    for s in samples[1:]:
        path += math.hypot(s[1] - prev[1], s[2] - prev[2])
        d = _yaw(s[4:8]) - _yaw(prev[4:8])
        turned += abs(math.atan2(math.sin(d), math.cos(d)))
        reach = max(reach, math.hypot(s[1] - x0, s[2] - y0))
        tilt = max(tilt, _tilt(s[4:8]))
        prev = s
    # forward / backward reversals: velocity along the heading over 0.5 s windows
    reversals, sign, last = 0, 0, samples[0]
    for s in samples[1:]:
        if s[0] - last[0] < 0.5:
            continue
        h = _yaw(last[4:8])
        v = ((s[1] - last[1]) * math.cos(h) + (s[2] - last[2]) * math.sin(h)) / (s[0] - last[0])
        if abs(v) > 0.03:
            sg = 1 if v > 0 else -1
            if sign and sg != sign:
                reversals += 1
            sign = sg
        last = s
    return {'duration': samples[-1][0] - samples[0][0], 'path': path, 'reach': reach,
            'turned': turned, 'reversals': reversals, 'tilt': tilt}


def pushed(objects):
    """[(name, moved m, turned rad)] of scene objects that moved beyond the tolerances;
    objects = {name: (first pose, last pose)} with poses (x, y, z, qx, qy, qz, qw)."""
    out = []
    for name, (a, b) in sorted(objects.items()):
        moved = math.sqrt(sum((p - q) ** 2 for p, q in zip(a[:3], b[:3])))
        d = _yaw(b[3:7]) - _yaw(a[3:7])
        turned = abs(math.atan2(math.sin(d), math.cos(d)))
        if moved > PUSH_TOL or turned > TURN_TOL or _tilt(b[3:7]) > _tilt(a[3:7]) + TURN_TOL:
            out.append((name, moved, turned))
    return out
