#!/usr/bin/env python3
"""velocity_controllers through spawner on the test robot's sim time."""
import sys
import threading
import time
import unittest

import rospy
import rostest
from course_testing.rosout import RosoutProbe, rosout_connected
from control_msgs.msg import JointControllerState
from controller_manager_msgs.srv import ListControllers, LoadController
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64, Float64MultiArray

WALL_TIMEOUT = 60.0
RUNNING = ['joint_state_controller', 'wheel_controller', 'position_controller',
           'group_velocity_controller']


class VelocityControllersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_velocity_controllers')
        cls.lock = threading.Lock()
        cls.js = None
        cls.state = None
        cls.logs = []
        rospy.Subscriber('/joint_states', JointState, cls._set, 'js')
        rospy.Subscriber('/position_controller/state', JointControllerState, cls._set, 'state')
        cls.rosout = rospy.Subscriber('/rosout', Log, lambda m: cls.logs.append(m.msg), queue_size=100)
        cls.pubs = {}
        rospy.wait_for_service('/controller_manager/list_controllers', WALL_TIMEOUT)
        lister = rospy.ServiceProxy('/controller_manager/list_controllers', ListControllers)
        cls.wait_for('every controller running', lambda: all(
            {c.name: c.state for c in lister().controller}.get(n) == 'running' for n in RUNNING))
        cls.wait_for('first /joint_states', lambda: cls.js is not None)
        cls.wait_for('/rosout of the robot', lambda: rosout_connected(cls.rosout, '/test_robot'))
        cls.wait_for('a line of /test_robot on /rosout', RosoutProbe(
            cls.logs, "'rosout_probe'",
            lambda: rospy.ServiceProxy('/controller_manager/load_controller', LoadController)('rosout_probe')))

    @classmethod
    def _set(cls, msg, attr):
        with cls.lock:
            setattr(cls, attr, msg)

    @classmethod
    def wait_for(cls, what, condition, sim_seconds=None):
        deadline = rospy.Time.now() + rospy.Duration(sim_seconds) if sim_seconds else None
        start = time.time()
        while not rospy.is_shutdown() and not condition():
            if deadline is not None and rospy.Time.now() > deadline:
                raise AssertionError('%s: not reached within %.1f s of sim time' % (what, sim_seconds))
            if time.time() - start > WALL_TIMEOUT:
                raise AssertionError('%s: not reached within %.0f s of wall time' % (what, WALL_TIMEOUT))
            time.sleep(0.01)

    def joint(self, name, field='position'):
        with self.lock:
            js = self.js
        return getattr(js, field)[js.name.index(name)]

    def publish(self, topic, msg_type, value):
        if topic not in self.pubs:
            self.pubs[topic] = rospy.Publisher(topic, msg_type, queue_size=1, latch=True)
        self.pubs[topic].publish(msg_type(data=value))

    def test_forwarder_starts_at_zero_and_forwards(self):
        self.assertEqual(self.joint('cont_joint', 'velocity'), 0.0)
        self.publish('/wheel_controller/command', Float64, 2.0)
        self.wait_for('cont_joint at 2 rad/s', lambda: self.joint('cont_joint', 'velocity') == 2.0, 5.0)
        self.publish('/wheel_controller/command', Float64, 0.0)

    def test_position_pid_to_velocity(self):
        self.publish('/position_controller/command', Float64, 1.0)
        self.wait_for('rev_joint at 1.0 rad', lambda: abs(self.joint('rev_joint') - 1.0) < 0.01, 10.0)
        self.wait_for('state published', lambda: self.state is not None and self.state.set_point == 1.0)
        self.assertEqual(self.state.p, 5.0)

    def test_group_forwarder_and_wrong_size(self):
        self.publish('/group_velocity_controller/command', Float64MultiArray, [0.5, -0.25])
        self.wait_for('group velocities', lambda: self.joint('g1_joint', 'velocity') == 0.5 and
                      self.joint('g2_joint', 'velocity') == -0.25, 5.0)
        self.publish('/group_velocity_controller/command', Float64MultiArray, [1.0, 2.0, 3.0])
        self.wait_for('size error logged', lambda: any(
            'Dimension of command (3) does not match number of joints (2)! Not executing!' in m
            for m in list(self.logs)))
        now = rospy.Time.now()
        self.wait_for('half a sim second', lambda: rospy.Time.now() > now + rospy.Duration(0.5))
        self.assertEqual(self.joint('g1_joint', 'velocity'), 0.5)
        self.publish('/group_velocity_controller/command', Float64MultiArray, [0.0, 0.0])

    def test_load_failures(self):
        load = rospy.ServiceProxy('/controller_manager/load_controller', LoadController)
        self.assertFalse(load('no_p_controller').ok)
        self.wait_for('missing p message', lambda: any(
            'No p gain specified for pid.  Namespace: /no_p_controller/pid' in m for m in list(self.logs)))
        self.assertFalse(load('no_joints_controller').ok)
        self.wait_for('missing joints message', lambda: any(
            "Failed to getParam 'joints' (namespace: /no_joints_controller)." in m for m in list(self.logs)))


if __name__ == '__main__':
    rostest.rosrun('velocity_controllers', 'velocity_controllers', VelocityControllersTest, sys.argv)
