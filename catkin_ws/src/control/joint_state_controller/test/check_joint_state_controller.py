#!/usr/bin/env python3
"""joint_state_controller through spawner on the test robot's sim time."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from course_testing.rosout import RosoutProbe, rosout_connected
from controller_manager_msgs.srv import ListControllers, LoadController
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import JointState

WALL_TIMEOUT = 60.0
MODE = 'all'   # argument from the .test file: all | subset


def wait_for(what, condition):
    start = time.time()
    while not rospy.is_shutdown() and not condition():
        if time.time() - start > WALL_TIMEOUT:
            raise AssertionError('%s: not reached within %.0f s of wall time' % (what, WALL_TIMEOUT))
        time.sleep(0.01)


class JointStateControllerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_joint_state_controller')
        cls.lock = threading.Lock()
        cls.msgs = {'/joint_states': []}
        cls.logs = []
        for topic in cls.msgs:
            rospy.Subscriber(topic, JointState, cls._js, topic, queue_size=100)
        cls.rosout = rospy.Subscriber('/rosout', Log, lambda m: cls.logs.append(m.msg), queue_size=100)
        rospy.wait_for_service('/controller_manager/list_controllers', WALL_TIMEOUT)
        wait_for('first messages', lambda: all(cls.msgs.values()))
        wait_for('/rosout of the robot', lambda: rosout_connected(cls.rosout, '/test_robot'))
        wait_for('a line of /test_robot on /rosout', RosoutProbe(
            cls.logs, "'rosout_probe'",
            lambda: rospy.ServiceProxy('/controller_manager/load_controller', LoadController)('rosout_probe')))

    @classmethod
    def _js(cls, msg, topic):
        with cls.lock:
            cls.msgs[topic].append(msg)

    def count_in(self, topic, start, seconds):
        """messages stamped in [start, start + seconds) of sim time"""
        end = start + rospy.Duration(seconds)
        wait_for('sim time past the window', lambda: rospy.Time.now() > end + rospy.Duration(0.2))
        with self.lock:
            return len([m for m in self.msgs[topic] if start <= m.header.stamp < end])

    def test_all_publishes_every_joint_at_publish_rate(self):
        start = rospy.Time.now() + rospy.Duration(0.1)
        # 100 in 2 s; a publish skipped while the publishing thread is busy comes one cycle
        # later, so a few may fall just outside the window on a loaded machine
        self.assertIn(self.count_in('/joint_states', start, 2.0), range(95, 102))
        with self.lock:
            msg = self.msgs['/joint_states'][-1]
        self.assertEqual(msg.name, ['a_joint', 'b_joint', 'c_joint'])   # interface order (sorted)
        self.assertEqual(list(msg.position), [0.0, 0.25, -0.5])
        self.assertEqual(len(msg.velocity), 3)
        self.assertEqual(len(msg.effort), 3)

    def test_subset_order_and_extra_joints(self):
        start = rospy.Time.now() + rospy.Duration(0.1)
        self.assertIn(self.count_in('/joint_states', start, 2.0), range(36, 42))
        with self.lock:
            msg = self.msgs['/joint_states'][-1]
        self.assertEqual(msg.name, ['b_joint', 'a_joint', 'fixed_extra'])
        self.assertEqual(list(msg.position), [0.25, 0.0, 0.5])
        self.assertEqual(msg.effort[2], -1.0)

    def test_all_missing_publish_rate_fails(self):
        load = rospy.ServiceProxy('/controller_manager/load_controller', LoadController)
        self.assertFalse(load('no_rate_controller').ok)
        wait_for('the original message', lambda: any("Parameter 'publish_rate' not set" in m
                                                     for m in list(self.logs)))
        self.assertFalse(load('unknown_joint_controller').ok)
        names = [c.name for c in rospy.ServiceProxy('/controller_manager/list_controllers',
                                                    ListControllers)().controller]
        self.assertNotIn('no_rate_controller', names)

    def test_all_malformed_extra_joint_is_skipped(self):
        load = rospy.ServiceProxy('/controller_manager/load_controller', LoadController)
        self.assertTrue(load('bad_extra_controller').ok)
        wait_for('the original message', lambda: any(
            "Extra joint 'bad_extra' does not specify a valid default position. Ignoring." in m
            for m in list(self.logs)))


if __name__ == '__main__':
    MODE = 'subset' if 'subset' in rospy.myargv(sys.argv)[1:] else 'all'
    for attr in list(vars(JointStateControllerTest)):
        if attr.startswith('test_') and not attr.startswith('test_%s_' % MODE):
            delattr(JointStateControllerTest, attr)
    rostest.rosrun('joint_state_controller', 'joint_state_controller', JointStateControllerTest, sys.argv)
