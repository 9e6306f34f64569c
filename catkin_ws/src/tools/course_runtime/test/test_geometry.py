"""course_runtime.geometry against Debian's tf.transformations (the reference)."""
import math
from collections import namedtuple

import numpy as np
import pytest
from tf import transformations as tft

from course_runtime.geometry import quaternion_wxyz, yaw_of, yaw_quaternion

Q = namedtuple('Q', 'x y z w')


@pytest.mark.parametrize('yaw', np.linspace(-math.pi + 1e-9, math.pi - 1e-9, 37))
def test_yaw_round_trip_and_tf(yaw):
    q = yaw_quaternion(yaw)
    assert q == pytest.approx(tuple(tft.quaternion_from_euler(0, 0, yaw)), abs=1e-12)
    assert yaw_of(Q(*q)) == pytest.approx(yaw, abs=1e-12)


def test_yaw_of_a_tilted_rotation_is_tfs():
    rng = np.random.default_rng(7)
    for _ in range(200):
        roll, pitch = rng.uniform(-1.2, 1.2, 2)
        yaw = rng.uniform(-math.pi, math.pi)
        q = tft.quaternion_from_euler(roll, pitch, yaw)
        assert yaw_of(Q(*q)) == pytest.approx(tft.euler_from_quaternion(q)[2], abs=1e-9)
        assert yaw_of(Q(*q)) == pytest.approx(yaw, abs=1e-9)


def test_quaternion_of_roll_pitch_yaw_is_tfs_w_first():
    rng = np.random.default_rng(11)
    for _ in range(200):
        roll, pitch, yaw = rng.uniform(-math.pi, math.pi, 3)
        x, y, z, w = tft.quaternion_from_euler(roll, pitch, yaw)
        assert quaternion_wxyz(roll, pitch, yaw) == pytest.approx((w, x, y, z), abs=1e-12)
    assert quaternion_wxyz(0.0, 0.0, 0.7) == pytest.approx((math.cos(0.35), 0.0, 0.0, math.sin(0.35)))
