#!/usr/bin/python3
"""rostest: ekf_localization_node fuses wheel odometry + IMU yaw rate (sim time) into `odom`
(remapped odometry/filtered) and TF odom->base_link; set_pose resets the state; an
out-of-order message is ignored."""
import time
import unittest

import rospy
import rostest
import tf2_ros
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu

from course_runtime.geometry import yaw_of
from robot_localization.srv import SetPose, SetPoseRequest

TIMEOUT = 60.0       # wall seconds for every wait
V, W = 0.5, 0.2      # m/s, rad/s


class EkfNodeTest(unittest.TestCase):
    def setUp(self):
        self.clock = rospy.Publisher('/clock', Clock, queue_size=1)
        self.odom_pub = rospy.Publisher('odom_wheel', Odometry, queue_size=10)
        self.imu_pub = rospy.Publisher('imu/data', Imu, queue_size=10)
        self.out = []
        rospy.Subscriber('odom', Odometry, self.out.append)
        self.buf = tf2_ros.Buffer()
        self.listener = tf2_ros.TransformListener(self.buf)
        self.t = 1.0

    def drive(self, seconds, wall_timeout=TIMEOUT, stamp_offset=0.0):
        end = time.time() + wall_timeout
        steps = int(seconds * 50)
        for _ in range(steps):
            if time.time() > end:
                break
            stamp = rospy.Time.from_sec(self.t)
            self.clock.publish(Clock(clock=stamp))
            o = Odometry()
            o.header.stamp = rospy.Time.from_sec(self.t + stamp_offset)
            o.header.frame_id, o.child_frame_id = 'odom', 'base_link'
            o.twist.twist.linear.x = V
            o.twist.twist.angular.z = W * 1.2        # slipping wheels over-report rotation
            o.twist.covariance = [0.0] * 36
            for i, v in enumerate([1e-3, 1e-3, 1e6, 1e6, 1e6, 0.1]):
                o.twist.covariance[i * 7] = v
            self.odom_pub.publish(o)
            m = Imu()
            m.header.stamp = stamp
            m.header.frame_id = 'base_link'
            m.orientation.w = 1.0
            m.angular_velocity.z = W
            m.angular_velocity_covariance = [1e-4, 0, 0, 0, 1e-4, 0, 0, 0, 1e-4]
            self.imu_pub.publish(m)
            self.t += 0.02
            time.sleep(0.01)

    def wait_connected(self):
        end = time.time() + TIMEOUT
        while time.time() < end and (self.odom_pub.get_num_connections() == 0 or
                                     self.imu_pub.get_num_connections() == 0):
            self.clock.publish(Clock(clock=rospy.Time.from_sec(self.t)))
            time.sleep(0.05)
        self.assertGreater(self.odom_pub.get_num_connections(), 0,
                           'ekf_localization_node did not subscribe odom_wheel within %.0f s' % TIMEOUT)

    def test_fusion_tf_set_pose(self):
        self.wait_connected()
        self.drive(4.0)
        self.assertGreater(len(self.out), 20, 'only %d messages on odom (odometry/filtered remapped)'
                           % len(self.out))
        last = self.out[-1]
        self.assertEqual(last.header.frame_id, 'odom')
        self.assertEqual(last.child_frame_id, 'base_link')
        elapsed = last.header.stamp.to_sec() - 1.0
        yaw = yaw_of(last.pose.pose.orientation)
        # IMU yaw rate dominates the slipping wheels: yaw ~ W * t, not 1.2 * W * t
        self.assertAlmostEqual(yaw, W * elapsed, delta=0.1 * W * elapsed + 0.02)
        self.assertAlmostEqual(last.twist.twist.linear.x, V, delta=0.05)
        tr = self.buf.lookup_transform('odom', 'base_link', rospy.Time(0), rospy.Duration(TIMEOUT))
        self.assertAlmostEqual(tr.transform.translation.x, last.pose.pose.position.x, delta=0.2)

        rospy.wait_for_service('set_pose', TIMEOUT)
        req = SetPoseRequest()
        req.pose.header.stamp = rospy.Time.from_sec(self.t)
        req.pose.header.frame_id = 'odom'
        req.pose.pose.pose.position.x = 10.0
        req.pose.pose.pose.orientation.w = 1.0
        req.pose.pose.covariance = [0.01 if i % 7 == 0 else 0.0 for i in range(36)]
        rospy.ServiceProxy('set_pose', SetPose)(req)
        n = len(self.out)
        self.drive(1.0)
        self.assertGreater(len(self.out), n, 'no output after set_pose')
        after = self.out[-1]
        self.assertAlmostEqual(after.pose.pose.position.x, 10.0 + V * 1.0, delta=0.3)


if __name__ == '__main__':
    rospy.init_node('check_ekf')
    rostest.rosrun('robot_localization', 'ekf_localization_node', EkfNodeTest)
