#!/usr/bin/env python3
"""rostest node: robot_description params loaded by both `command=` forms are expanded URDF."""
import sys
import unittest
import xml.etree.ElementTree as ET

import rospy
import rostest


class RobotDescription(unittest.TestCase):
    def _urdf(self, name):
        text = rospy.get_param(name)
        self.assertNotIn('xacro:', text)
        return ET.fromstring(text)

    def test_find_xacro_form(self):
        robot = self._urdf('/robot_description')
        self.assertEqual(robot.get('name'), 'fixture_bot')
        links = [l.get('name') for l in robot.findall('link')]
        self.assertEqual(links, ['by_find_footprint', 'base_link', 'left_wheel', 'right_wheel', 'laser'])

    def test_xacro_on_path_form(self):
        robot = self._urdf('/robot_description_path')
        self.assertEqual(robot.get('name'), 'fixture_bot')
        links = [l.get('name') for l in robot.findall('link')]
        self.assertEqual(links, ['fixture_bot_footprint', 'base_link', 'left_wheel', 'right_wheel', 'no_laser'])


if __name__ == '__main__':
    rospy.init_node('check_robot_description')
    rostest.rosrun('xacro', 'check_robot_description', RobotDescription, sys.argv)
