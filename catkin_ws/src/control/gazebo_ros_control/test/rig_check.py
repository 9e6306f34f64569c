#!/usr/bin/env python3
"""rig.test: the swing joint held at 1.5 rad by effort_controllers/JointPositionController, the
wheel at 2 rad/s by velocity_controllers/JointVelocityController, the tilt joint held still
against gravity; all judged on sim time from /rig/joint_states (joint_state_controller)."""
import threading
import time
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

WALL_TIMEOUT = 90.0     # generous: the machine may be slow; all judgements are on sim time
HOLD_TOLERANCE = 0.02   # rad
VELOCITY_TOLERANCE = 0.02  # relative


class RigTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.states = []
        rospy.Subscriber('/rig/joint_states', JointState, self.on_state, queue_size=100)

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

    def test_hold_and_velocity(self):
        rospy.wait_for_service('/rig/controller_manager/list_controllers', WALL_TIMEOUT)
        lc = rospy.ServiceProxy('/rig/controller_manager/list_controllers', ListControllers)

        def running():
            states = {c.name: c.state for c in lc().controller}
            return len(states) == 4 and all(s == 'running' for s in states.values())
        self.wait(running, 'the 4 controllers running in /rig (spawner)')
        self.wait(lambda: self.states, '/rig/joint_states')
        swing = rospy.Publisher('/rig/swing_position_controller/command', Float64, queue_size=1, latch=True)
        wheel = rospy.Publisher('/rig/wheel_velocity_controller/command', Float64, queue_size=1, latch=True)
        swing.publish(Float64(1.5))
        wheel.publish(Float64(2.0))
        t0 = self.sim_now()
        self.wait(lambda: self.sim_now() > t0 + 4.0, '4 s of sim time after the commands')
        with self.lock:
            late = [s for s in self.states if s.header.stamp.to_sec() > t0 + 3.0]
        self.assertGreater(len(late), 10, 'joint_states at 50 Hz: too few in 1 s of sim time')
        for s in late:
            q = dict(zip(s.name, s.position))
            v = dict(zip(s.name, s.velocity))
            t = s.header.stamp.to_sec()
            self.assertAlmostEqual(q['swing_joint'], 1.5, delta=HOLD_TOLERANCE,
                                   msg='swing_joint at t=%.3f: %.4f rad, want 1.5' % (t, q['swing_joint']))
            self.assertAlmostEqual(v['wheel_joint'], 2.0, delta=2.0 * VELOCITY_TOLERANCE,
                                   msg='wheel_joint at t=%.3f: %.4f rad/s, want 2.0' % (t, v['wheel_joint']))
        # the tilt arm fell until its controller started, which then holds it where it was
        tilt = [dict(zip(s.name, s.position))['tilt_joint'] for s in late]
        self.assertLess(max(tilt) - min(tilt), 0.005, 'tilt_joint not held: %s' % tilt)


if __name__ == '__main__':
    rospy.init_node('rig_check')
    rostest.rosrun('gazebo_ros_control', 'rig_check', RigTest)
