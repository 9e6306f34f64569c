#!/usr/bin/python3
"""rostest: obstacle_cloud_filter_node turns a floor + box + far-wall cloud on `points` into an
`obstacles` cloud holding the box only (same header)."""
import time
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs import point_cloud2
from sensor_msgs.msg import PointCloud2
from std_msgs.msg import Header

TIMEOUT = 60.0    # wall seconds


def scene():
    g = np.linspace(0.0, 1.0, 60)
    s, t = np.meshgrid(g, g)
    floor = np.stack([0.3 + 2.7 * t, -1 + 2 * s, np.zeros_like(s)], -1).reshape(-1, 3)
    box = np.stack([np.full_like(s, 1.0), -0.15 + 0.3 * s, 0.3 * t], -1).reshape(-1, 3)
    top = np.stack([1.0 + 0.3 * t, -0.15 + 0.3 * s, np.full_like(s, 0.3)], -1).reshape(-1, 3)
    wall = np.stack([np.full_like(s, 5.0), -2 + 4 * s, 2 * t], -1).reshape(-1, 3)
    nan = np.full((10, 3), np.nan)
    return np.concatenate([floor, floor + [0.01, 0.01, 0], box, top, wall, nan])


class ObstacleCloudFilterTest(unittest.TestCase):
    def test_box_only(self):
        got = []
        rospy.Subscriber('obstacles', PointCloud2, got.append)
        pub = rospy.Publisher('points', PointCloud2, queue_size=1)
        header = Header(frame_id='camera_link', stamp=rospy.Time(12, 34))
        cloud = point_cloud2.create_cloud_xyz32(header, scene().tolist())
        end = time.time() + TIMEOUT
        while not got and time.time() < end:
            if pub.get_num_connections():
                pub.publish(cloud)
            time.sleep(0.2)
        self.assertTrue(got, 'no message on obstacles within %.0f s' % TIMEOUT)
        out = got[0]
        self.assertEqual(out.header.frame_id, 'camera_link')
        self.assertEqual(out.header.stamp, rospy.Time(12, 34))
        pts = np.array(list(point_cloud2.read_points(out, ('x', 'y', 'z'))))
        self.assertGreater(len(pts), 50)
        self.assertTrue(np.all(pts[:, 0] <= 3.0), 'far-wall points passed')
        in_box = (pts[:, 0] >= 0.98) & (pts[:, 0] <= 1.32) & (np.abs(pts[:, 1]) <= 0.17)
        self.assertGreaterEqual(in_box.mean(), 0.95, 'floor points left: %s' % pts[~in_box][:5])


if __name__ == '__main__':
    rospy.init_node('check_obstacle_cloud_filter')
    rostest.rosrun('obstacle_cloud_filter', 'obstacle_cloud_filter_node', ObstacleCloudFilterTest)
