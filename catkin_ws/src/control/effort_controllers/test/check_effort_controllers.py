#!/usr/bin/env python3
"""effort_controllers driven like a user does: spawner + YAML, commands on `<ctrl>/command`,
state on `<ctrl>/state` and /joint_states, on the test robot's sim time."""
import math
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

WALL_TIMEOUT = 60.0   # generous bound on every wait [wall s]
RUNNING = ['joint_state_controller', 'position_controller', 'continuous_position_controller',
           'prismatic_position_controller', 'group_position_controller', 'effort_controller']


class Fixture(object):
    def __init__(self):
        self.lock = threading.Lock()
        self.joint_states = None
        self.states = {}
        self.logs = []
        rospy.Subscriber('/joint_states', JointState, self._js)
        self.rosout = rospy.Subscriber('/rosout', Log, self._log)
        for name in ('position_controller', 'continuous_position_controller',
                     'prismatic_position_controller'):
            rospy.Subscriber('/%s/state' % name, JointControllerState, self._state, name)
        self.pubs = {}

    def _js(self, msg):
        with self.lock:
            self.joint_states = msg

    def _state(self, msg, name):
        with self.lock:
            self.states[name] = msg

    def _log(self, msg):
        with self.lock:
            self.logs.append(msg.msg)

    def position(self, joint):
        with self.lock:
            js = self.joint_states
        return None if js is None else js.position[js.name.index(joint)]

    def effort(self, joint):
        with self.lock:
            js = self.joint_states
        return None if js is None else js.effort[js.name.index(joint)]

    def publish(self, topic, msg_type, value):
        if topic not in self.pubs:
            self.pubs[topic] = rospy.Publisher(topic, msg_type, queue_size=1, latch=True)
        self.pubs[topic].publish(msg_type(data=value))

    def wait_for(self, what, condition, sim_seconds=None):
        """Wait until condition() is true; optionally fail after `sim_seconds` of sim time."""
        deadline = rospy.Time.now() + rospy.Duration(sim_seconds) if sim_seconds else None
        wall_start = time.time()
        while not rospy.is_shutdown():
            if condition():
                return
            if deadline is not None and rospy.Time.now() > deadline:
                raise AssertionError('%s: not reached within %.1f s of sim time' % (what, sim_seconds))
            if time.time() - wall_start > WALL_TIMEOUT:
                raise AssertionError('%s: not reached within %.0f s of wall time' % (what, WALL_TIMEOUT))
            time.sleep(0.01)


class EffortControllersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_effort_controllers')
        cls.f = Fixture()
        rospy.wait_for_service('/controller_manager/list_controllers', WALL_TIMEOUT)
        cls.list = rospy.ServiceProxy('/controller_manager/list_controllers', ListControllers)
        cls.load = rospy.ServiceProxy('/controller_manager/load_controller', LoadController)

        def all_running():
            states = {c.name: c.state for c in cls.list().controller}
            return all(states.get(n) == 'running' for n in RUNNING)
        cls.f.wait_for('spawner starts every controller', all_running)
        cls.f.wait_for('first /joint_states', lambda: cls.f.joint_states is not None)
        cls.f.wait_for('/rosout of the robot', lambda: rosout_connected(cls.f.rosout, '/test_robot'))
        cls.f.wait_for('a line of /test_robot on /rosout',
                       RosoutProbe(cls.f.logs, "'rosout_probe'", lambda: cls.load('rosout_probe')))

    def test_position_controller_converges(self):
        f = self.f
        f.publish('/position_controller/command', Float64, 1.5)
        f.wait_for('rev_joint at 1.5 rad', lambda: abs(f.position('rev_joint') - 1.5) < 0.01, 10.0)
        f.wait_for('state topic', lambda: 'position_controller' in f.states)
        with f.lock:
            state = f.states['position_controller']
        self.assertEqual(state.set_point, 1.5)
        self.assertEqual((state.p, state.i, state.d), (100.0, 0.01, 10.0))
        self.assertFalse(state.antiwindup)

    def test_position_pid_tuned_with_dynamic_reconfigure(self):
        # practical work 5's self-study: tune the PID while it runs
        import dynamic_reconfigure.client
        client = dynamic_reconfigure.client.Client('/prismatic_position_controller/pid', timeout=WALL_TIMEOUT)
        client.update_configuration({'p': 150.0, 'd': 25.0})
        f = self.f

        def gains_in_state():
            with f.lock:
                s = f.states.get('prismatic_position_controller')
            return s is not None and (s.p, s.d) == (150.0, 25.0)
        f.wait_for('new gains in the state topic', gains_in_state, 5.0)
        self.assertEqual(rospy.get_param('/prismatic_position_controller/pid/p'), 150.0)

    def test_position_set_point_clamped_to_limits(self):
        f = self.f
        f.publish('/prismatic_position_controller/command', Float64, 2.0)   # limit 0.5
        f.wait_for('pris_joint at its 0.5 m limit',
                   lambda: abs(f.position('pris_joint') - 0.5) < 0.005, 10.0)

        def set_point_clamped():
            with f.lock:
                s = f.states.get('prismatic_position_controller')
            return s is not None and s.set_point == 0.5
        f.wait_for('state.set_point clamped to 0.5', set_point_clamped, 5.0)

    def test_continuous_joint_takes_the_short_way(self):
        f = self.f
        # from 3.0 rad to -3.0 rad: the short way is +0.28 rad through pi
        f.publish('/continuous_position_controller/command', Float64, -3.0)
        target = 3.0 + (2 * math.pi - 6.0)
        f.wait_for('cont_joint reaches -3.0 through pi',
                   lambda: abs(f.position('cont_joint') - target) < 0.01, 10.0)

    def test_group_position_controller(self):
        f = self.f
        f.publish('/group_position_controller/command', Float64MultiArray, [0.5, 0.2])
        f.wait_for('group at [0.5, 0.2]', lambda: abs(f.position('g1_joint') - 0.5) < 0.01 and
                   abs(f.position('g2_joint') - 0.2) < 0.01, 10.0)
        f.publish('/group_position_controller/command', Float64MultiArray, [0.1])   # wrong size
        f.wait_for('size error logged', lambda: any(
            'Dimension of command (1) does not match number of joints (2)! Not executing!' in m
            for m in list(f.logs)))
        now = rospy.Time.now()
        f.wait_for('one sim second', lambda: rospy.Time.now() > now + rospy.Duration(1.0))
        self.assertAlmostEqual(f.position('g1_joint'), 0.5, delta=0.01)

    def test_effort_forwarder(self):
        f = self.f
        f.publish('/effort_controller/command', Float64, 0.75)
        f.wait_for('effort 0.75 applied to eff_joint', lambda: f.effort('eff_joint') == 0.75, 5.0)
        f.publish('/effort_controller/command', Float64, float('nan'))
        now = rospy.Time.now()
        f.wait_for('half a sim second', lambda: rospy.Time.now() > now + rospy.Duration(0.5))
        self.assertEqual(f.effort('eff_joint'), 0.75)   # NaN dropped
        f.publish('/effort_controller/command', Float64, 0.0)

    def _load_fails_with(self, name, message):
        self.assertFalse(self.load(name).ok, '%s loaded although it is misconfigured' % name)
        self.f.wait_for('log "%s"' % message, lambda: any(message in m for m in list(self.f.logs)))

    def test_missing_joint_fails(self):
        self._load_fails_with('no_joint_controller', 'No joint given (namespace: /no_joint_controller)')

    def test_missing_p_gain_fails(self):
        self._load_fails_with('no_p_controller',
                              'No p gain specified for pid.  Namespace: /no_p_controller/pid')

    def test_unknown_joint_fails(self):
        self._load_fails_with('unknown_joint_controller', 'no_such_joint')

    def test_group_without_gains_fails(self):
        self._load_fails_with('no_gains_group_controller',
                              'No p gain specified for pid.  Namespace: /no_gains_group_controller/gains/g1_joint')

    def test_velocity_pid_controller_loads(self):
        self.assertTrue(self.load('velocity_pid_controller').ok)


if __name__ == '__main__':
    rostest.rosrun('effort_controllers', 'effort_controllers', EffortControllersTest, sys.argv)
