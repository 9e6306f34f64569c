"""The message conversions (no master needed)."""
import math

import numpy as np
import pytest
from geometry_msgs.msg import PoseWithCovarianceStamped, TransformStamped
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan

from amcl import convert


def grid():
    m = OccupancyGrid()
    m.info.width, m.info.height, m.info.resolution = 3, 2, 0.5
    m.info.origin.position.x, m.info.origin.position.y = -1.0, 2.0
    m.data = [0, 100, -1, 50, 0, 100]
    return m


def test_map_from_msg_trinary_like_amcl():
    gm = convert.map_from_msg(grid())
    assert gm.cells.tolist() == [[-1, 1, 0], [0, -1, 1]]
    assert (gm.origin_x, gm.origin_y, gm.resolution) == (-1.0, 2.0, 0.5)
    i, j = gm.world_to_map(np.array([-0.75]), np.array([2.75]))
    assert (i[0], j[0]) == (0, 1)


def test_map_with_wrong_data_length_rejected():
    m = grid()
    m.data = [0, 0]
    with pytest.raises(ValueError, match='expected 3 x 2'):
        convert.map_from_msg(m)


def laser_tf(roll=0.0, yaw=0.0):
    t = TransformStamped()
    t.transform.translation.x = 0.1
    cr, sr, cy, sy = math.cos(roll / 2), math.sin(roll / 2), math.cos(yaw / 2), math.sin(yaw / 2)
    t.transform.rotation.x, t.transform.rotation.y = sr * cy, -sr * sy
    t.transform.rotation.z, t.transform.rotation.w = cr * sy, cr * cy
    return t


def scan():
    s = LaserScan()
    s.angle_min, s.angle_increment = -0.5, 0.5
    s.range_min, s.range_max = 0.15, 12.0
    s.ranges = [0.1, 1.0, float('inf')]
    return s


def test_laser_data_ranges_and_bearings():
    d = convert.laser_data(scan(), laser_tf(yaw=0.2), max_range=8.0)
    assert d.range_max == 8.0
    assert d.ranges.tolist() == [8.0, 1.0, 8.0]          # below min -> max, inf -> max
    assert d.angles == pytest.approx([-0.3, 0.2, 0.7])
    assert d.laser_pose[0] == pytest.approx(0.1)


def test_upside_down_laser_reverses_bearings():
    d = convert.laser_data(scan(), laser_tf(roll=math.pi))
    assert d.angles == pytest.approx([0.5, 0.0, -0.5], abs=1e-9)


def test_pose_messages_round_trip():
    cov = np.diag([0.1, 0.2, 0.3])
    msg = convert.pose_with_covariance((1.0, 2.0, 0.5), cov, None, 'map')
    assert isinstance(msg, PoseWithCovarianceStamped) and msg.header.frame_id == 'map'
    assert msg.pose.covariance[0] == 0.1 and msg.pose.covariance[7] == 0.2 and msg.pose.covariance[35] == 0.3
    mean, c = convert.initial_pose_from_msg(msg)
    assert mean == pytest.approx([1.0, 2.0, 0.5]) and np.allclose(c, cov)
    t = convert.transform((1.0, -1.0, -2.0), None, 'map', 'odom')
    assert convert.pose_from_transform(t) == pytest.approx([1.0, -1.0, -2.0])
