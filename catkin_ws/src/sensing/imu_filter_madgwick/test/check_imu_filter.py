#!/usr/bin/python3
"""rostest: imu_filter_node turns a tilted, still imu/data_raw stream (sim time) into imu/data
with the right roll/pitch, the input's header and a TF odom -> imu frame."""
import math
import time
import unittest

import rospy
import rostest
import tf2_ros
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu

from imu_filter_madgwick.filter import quat_from_rpy, quat_conj, rotate, quat_to_rpy

ROLL, PITCH = 0.3, -0.2
TIMEOUT = 60.0   # wall seconds for every wait


class ImuFilterNodeTest(unittest.TestCase):
    def test_filtered_orientation_and_tf(self):
        clock = rospy.Publisher('/clock', Clock, queue_size=1, latch=True)
        raw = rospy.Publisher('imu/data_raw', Imu, queue_size=10)
        out = []
        rospy.Subscriber('imu/data', Imu, out.append)
        buf = tf2_ros.Buffer()
        tf2_ros.TransformListener(buf)
        q = quat_from_rpy(ROLL, PITCH, 0.0)
        g = rotate(quat_conj(q), (0, 0, 9.80665))
        end = time.time() + TIMEOUT
        t = 1.0
        while time.time() < end and (len(out) < 50 or raw.get_num_connections() == 0):
            stamp = rospy.Time.from_sec(t)
            clock.publish(Clock(clock=stamp))
            m = Imu()
            m.header.stamp = stamp
            m.header.frame_id = 'imu_link'
            m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z = g
            raw.publish(m)
            t += 0.01
            time.sleep(0.005)
        self.assertGreaterEqual(len(out), 50, 'imu_filter_node published %d messages on imu/data '
                                '(expected 50) within %.0f s' % (len(out), TIMEOUT))
        last = out[-1]
        self.assertEqual(last.header.frame_id, 'imu_link')
        o = last.orientation
        r, p, _ = quat_to_rpy((o.w, o.x, o.y, o.z))
        self.assertAlmostEqual(r, ROLL, delta=math.radians(1.0))
        self.assertAlmostEqual(p, PITCH, delta=math.radians(1.0))
        tr = buf.lookup_transform('odom', 'imu_link', rospy.Time(0), rospy.Duration(TIMEOUT))
        r2, p2, _ = quat_to_rpy((tr.transform.rotation.w, tr.transform.rotation.x,
                                 tr.transform.rotation.y, tr.transform.rotation.z))
        self.assertAlmostEqual(r2, ROLL, delta=math.radians(1.0))


if __name__ == '__main__':
    rospy.init_node('check_imu_filter')
    rostest.rosrun('imu_filter_madgwick', 'imu_filter_node', ImuFilterNodeTest)
