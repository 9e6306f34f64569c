#!/usr/bin/env python3
"""Practical work 5 check (rostest node): commands the controllers of /diffrobot as the student
does with `rostopic pub -1 /diffrobot/<controller>/command std_msgs/Float64 "data: X"` and
judges /diffrobot/joint_states on sim time.
~mode: position (joint1_position_controller to ~target rad, the joint within ~tolerance)
       velocity (both wheels' velocity controllers to ~target rad/s, mean velocity within
       ~tolerance relative)."""
import threading
import time
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

WALL_TIMEOUT = 100.0


class WheelCheck(unittest.TestCase):
    def setUp(self):
        self.mode = rospy.get_param('~mode', 'position')
        self.target = float(rospy.get_param('~target', 1.5))
        self.tolerance = float(rospy.get_param('~tolerance', 0.02))
        self.lock = threading.Lock()
        self.states = []
        rospy.Subscriber('/diffrobot/joint_states', JointState, self.on_state, queue_size=100)

    def on_state(self, msg):
        with self.lock:
            self.states.append(msg)

    def wait(self, cond, what):
        end = time.monotonic() + WALL_TIMEOUT
        while not cond():
            if rospy.is_shutdown() or time.monotonic() > end:
                self.fail('timed out (%.0f s wall) waiting for %s' % (WALL_TIMEOUT, what))
            time.sleep(0.05)

    def sim_now(self):
        with self.lock:
            return self.states[-1].header.stamp.to_sec() if self.states else 0.0

    def test_command(self):
        rospy.wait_for_service('/diffrobot/controller_manager/list_controllers', WALL_TIMEOUT)
        lc = rospy.ServiceProxy('/diffrobot/controller_manager/list_controllers', ListControllers)
        names = (['joint1_position_controller'] if self.mode == 'position'
                 else ['joint1_velocity_controller', 'joint2_velocity_controller'])

        def running():
            states = {c.name: c.state for c in lc().controller}
            return all(states.get(n) == 'running' for n in names + ['joint_state_controller'])
        self.wait(running, 'the controllers %s running in /diffrobot' % names)
        self.wait(lambda: self.states, '/diffrobot/joint_states')
        pubs = [rospy.Publisher('/diffrobot/%s/command' % n, Float64, queue_size=1, latch=True) for n in names]
        for p in pubs:
            p.publish(Float64(self.target))
        t0 = self.sim_now()
        self.wait(lambda: self.sim_now() > t0 + 5.0, '5 s of sim time after the command')
        with self.lock:
            late = [s for s in self.states if s.header.stamp.to_sec() > t0 + 4.0]
        self.assertGreater(len(late), 10, 'too few joint_states in 1 s of sim time')
        for s in late:
            q = dict(zip(s.name, s.position))
            t = s.header.stamp.to_sec()
            if self.mode == 'position':
                self.assertAlmostEqual(q['wheel_left_joint'], self.target, delta=self.tolerance,
                                       msg='wheel_left_joint at t=%.3f: %.4f rad, want %.3f'
                                       % (t, q['wheel_left_joint'], self.target))
        if self.mode == 'velocity':
            for j in ('wheel_left_joint', 'wheel_right_joint'):
                mean = sum(dict(zip(s.name, s.velocity))[j] for s in late) / len(late)
                self.assertAlmostEqual(mean, self.target, delta=self.tolerance * abs(self.target),
                                       msg='%s: mean velocity %.3f rad/s, want %.3f' % (j, mean, self.target))


if __name__ == '__main__':
    rospy.init_node('check_wheels')
    rostest.rosrun('my_robot_simulation_control', 'check_wheels', WheelCheck)
