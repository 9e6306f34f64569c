"""costmap_2d's message conversions without a master: scans, clouds, grids."""
import math
import struct

import pytest
from sensor_msgs.msg import LaserScan, PointCloud2, PointField

from costmap_2d import conversions as conv
from costmap_2d.costmap import Costmap2D


def test_scan_to_points_drops_out_of_range_and_handles_inf():
    s = LaserScan()
    s.angle_min, s.angle_increment = 0.0, math.pi / 2
    s.range_min, s.range_max = 0.15, 12.0
    s.ranges = [1.0, float('inf'), 0.1, 2.0]
    pts = conv.scan_to_points(s)
    assert pts.shape == (2, 3)
    assert pts[0] == pytest.approx([1.0, 0.0, 0.0])
    assert pts[1] == pytest.approx([0.0, -2.0, 0.0], abs=1e-9)
    pts = conv.scan_to_points(s, inf_is_valid=True)
    assert len(pts) == 3 and pts[1][1] == pytest.approx(12.0 - 0.0001)


def test_cloud2_to_points():
    c = PointCloud2()
    c.fields = [PointField('x', 0, PointField.FLOAT32, 1), PointField('y', 4, PointField.FLOAT32, 1),
                PointField('z', 8, PointField.FLOAT32, 1),
                PointField('intensity', 12, PointField.FLOAT32, 1)]
    c.point_step, c.height, c.width = 16, 1, 3
    c.data = b''.join(struct.pack('<4f', *p) for p in
                      [(1, 2, 3, 9), (float('nan'), 0, 0, 0), (-1, 0.5, 0.25, 1)])
    c.row_step = 48
    pts = conv.cloud2_to_points(c)
    assert pts.tolist() == [[1, 2, 3], [-1, 0.5, 0.25]]


def test_costmap_to_grid_values():
    m = Costmap2D(4, 1, 0.5, -1.0, 2.0)
    m.data[0, :] = [0, 253, 254, 255]
    import rospy
    g = conv.costmap_to_grid(m, 'map', rospy.Time(0))
    assert list(g.data) == [0, 99, 100, -1]
    assert (g.info.width, g.info.height, g.info.resolution) == (4, 1, 0.5)
    assert (g.info.origin.position.x, g.info.origin.position.y) == (-1.0, 2.0)
