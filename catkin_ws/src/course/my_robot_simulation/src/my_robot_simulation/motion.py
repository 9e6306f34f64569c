"""Velocity patterns for scripts/drive.py (self-study 2 of practical work 4: a script that
publishes to /cmd_vel). Pure functions of time, no ROS: `command(pattern, t, ...)` gives the
(linear m/s, angular rad/s) pair to publish at time t seconds after the start."""
import math

PATTERNS = ('forward', 'circle', 'square', 'spin', 'zigzag')


class MotionError(ValueError):
    """A bad pattern or parameter: the message is one line naming it."""


def check(pattern, speed, turn_rate, side):
    if pattern not in PATTERNS:
        raise MotionError('unknown pattern %r: use one of %s' % (pattern, ', '.join(PATTERNS)))
    for name, value in (('speed', speed), ('turn_rate', turn_rate), ('side', side)):
        if not isinstance(value, (int, float)) or not math.isfinite(value):
            raise MotionError('%s must be a number, got %r' % (name, value))
    if pattern == 'square':
        if speed <= 0 or side <= 0 or turn_rate <= 0:
            raise MotionError('square needs speed, side and turn_rate > 0 (got %g, %g, %g)'
                              % (speed, side, turn_rate))


def command(pattern, t, speed=0.2, turn_rate=0.5, side=1.0):
    """(v, w) of `pattern` at time t >= 0:
    forward: straight at `speed`; circle: `speed` and `turn_rate` together (radius
    speed/turn_rate); spin: turn in place at `turn_rate`; square: `side` metres straight, then a
    90 degree turn in place at `turn_rate`, repeated; zigzag: straight, alternating the turn
    direction every side/speed seconds."""
    check(pattern, speed, turn_rate, side)
    if t < 0:
        raise MotionError('time must be >= 0, got %g' % t)
    if pattern == 'forward':
        return speed, 0.0
    if pattern == 'circle':
        return speed, turn_rate
    if pattern == 'spin':
        return 0.0, turn_rate
    if pattern == 'zigzag':
        period = side / speed if speed else 1.0
        return speed, turn_rate if int(t // period) % 2 == 0 else -turn_rate
    straight = side / speed
    turn = (math.pi / 2) / turn_rate
    phase = t % (straight + turn)
    return (speed, 0.0) if phase < straight else (0.0, turn_rate)


def square_period(speed=0.2, turn_rate=0.5, side=1.0):
    """Seconds one side plus one corner of the square take."""
    check('square', speed, turn_rate, side)
    return side / speed + (math.pi / 2) / turn_rate


def integrate(pattern, duration, dt=0.01, **kw):
    """Ideal unicycle pose (x, y, yaw) after following `pattern` for `duration` seconds from
    (0, 0, 0): what a perfect diff-drive robot would do (used to check the patterns)."""
    x = y = yaw = 0.0
    n = int(round(duration / dt))
    for i in range(n):
        v, w = command(pattern, i * dt, **kw)
        x += v * math.cos(yaw) * dt
        y += v * math.sin(yaw) * dt
        yaw += w * dt
    return x, y, yaw
