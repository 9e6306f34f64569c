"""Lidar processing of sensor_data_proc.py without a roscore."""
import math

from sensor_msgs.msg import LaserScan

from my_robot_simulation_sensors import scan_proc as sp


def scan(ranges, amin=-0.785, amax=0.785):
    n = len(ranges)
    return LaserScan(angle_min=amin, angle_max=amax, angle_increment=(amax - amin) / (n - 1),
                     range_min=0.03, range_max=3.0, ranges=ranges)


def test_nearest_and_sectors():
    r = [math.inf] * 90
    r[10] = 2.5          # right
    r[45] = 1.2          # front
    r[80] = 0.8          # left
    r[0] = 0.01          # below range_min: no echo
    s = scan(r)
    d, bearing = sp.nearest(s)
    assert d == 0.8 and bearing > 0.5
    assert sp.sectors(s) == [2.5, 1.2, 0.8]
    line = sp.describe(s)
    assert '90 rays' in line and 'nearest 0.80 m' in line and 'front 1.20' in line


def test_empty_scan():
    s = scan([math.inf, math.nan, 5.0])
    assert sp.nearest(s) is None
    assert sp.sectors(s) == [math.inf] * 3
    assert 'nothing in range' in sp.describe(s)
