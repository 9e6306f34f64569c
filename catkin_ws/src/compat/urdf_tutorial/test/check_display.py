#!/usr/bin/env python3
"""rostest node: display.launch loads robot_description and publishes joint states and /tf."""
import sys
import unittest
import xml.etree.ElementTree as ET

import rospy
import rostest
import tf2_ros

WHEELS = ['front_left', 'front_right', 'rear_left', 'rear_right']


class Display(unittest.TestCase):
    def test_robot_description(self):
        robot = ET.fromstring(rospy.get_param('/robot_description'))
        self.assertEqual(robot.get('name'), 'cart')
        self.assertEqual(sorted(l.get('name') for l in robot.findall('link')),
                         sorted(['base_link', 'mast'] + [w + '_wheel' for w in WHEELS]))

    def test_joint_states(self):
        from sensor_msgs.msg import JointState
        msg = rospy.wait_for_message('/joint_states', JointState, timeout=20)
        self.assertEqual(sorted(msg.name),
                         sorted(['mast_joint'] + [w + '_wheel_joint' for w in WHEELS]))

    def test_tf(self):
        buf = tf2_ros.Buffer()
        tf2_ros.TransformListener(buf)
        t = buf.lookup_transform('base_link', 'front_left_wheel', rospy.Time(0),
                                 rospy.Duration(20))
        # wheel origin: x = length/2 - r = 0.18, y = (width + w)/2 = 0.17, z = r = 0.07
        tr = t.transform.translation
        self.assertAlmostEqual(tr.x, 0.18, places=6)
        self.assertAlmostEqual(tr.y, 0.17, places=6)
        self.assertAlmostEqual(tr.z, 0.07, places=6)
        t = buf.lookup_transform('base_link', 'mast', rospy.Time(0), rospy.Duration(20))
        self.assertAlmostEqual(t.transform.translation.z, 0.19, places=6)


if __name__ == '__main__':
    rospy.init_node('check_display')
    rostest.rosrun('urdf_tutorial', 'check_display', Display, sys.argv)
