"""Velocity patterns of scripts/drive.py (no ROS)."""
import math

import pytest

from my_robot_simulation.motion import MotionError, command, integrate, square_period


def test_forward_and_spin():
    assert command('forward', 3.0, speed=0.3) == (0.3, 0.0)
    assert command('spin', 1.0, turn_rate=0.7) == (0.0, 0.7)


def test_square_closes():
    period = square_period(0.2, 0.5, 1.0)
    x, y, yaw = integrate('square', 4 * period, dt=0.001, speed=0.2, turn_rate=0.5, side=1.0)
    assert math.hypot(x, y) < 0.02
    assert abs(math.remainder(yaw, 2 * math.pi)) < 0.02


def test_square_first_side_then_corner():
    assert command('square', 1.0) == (0.2, 0.0)
    v, w = command('square', 5.0 + 0.1)       # 1 m at 0.2 m/s takes 5 s, then the turn
    assert v == 0.0 and w == 0.5


def test_circle_radius():
    x, y, yaw = integrate('circle', 2 * math.pi / 0.5, dt=0.001, speed=0.25, turn_rate=0.5)
    assert math.hypot(x, y) < 0.01          # a full circle of radius 0.5 m


def test_zigzag_alternates():
    assert command('zigzag', 0.1, speed=0.5, side=1.0)[1] > 0
    assert command('zigzag', 2.1, speed=0.5, side=1.0)[1] < 0


@pytest.mark.parametrize('args,text', [
    (('triangle', 0.0), 'unknown pattern'),
    (('square', 0.0, 0.0), 'square needs'),
    (('forward', -1.0), 'time must be'),
    (('forward', 0.0, float('nan')), 'speed must be a number'),
])
def test_bad_input_is_one_clear_error(args, text):
    with pytest.raises(MotionError) as e:
        command(*args)
    assert text in str(e.value) and '\n' not in str(e.value)
