#!/usr/bin/env python3
"""arm_sim.test: the effort JointTrajectoryController moves a simulated two-link arm (ode_sim,
lockstep, sim time): a goal through actionlib succeeds and the arm is where the trajectory ends;
an impossible path tolerance aborts with PATH_TOLERANCE_VIOLATED; a trajectory on the command
topic is followed; a cancel stops the arm short of the goal."""
import threading
import time
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (FollowJointTrajectoryAction, FollowJointTrajectoryGoal,
                              FollowJointTrajectoryResult, JointTolerance, JointTrajectoryControllerState)
from controller_manager_msgs.srv import ListControllers
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

WALL_TIMEOUT = 150.0  # hang guard only
JOINTS = ['shoulder', 'elbow']
TERMINAL = (GoalStatus.PREEMPTED, GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.REJECTED,
            GoalStatus.RECALLED, GoalStatus.LOST)


def traj(points):
    return JointTrajectory(joint_names=JOINTS, points=[
        JointTrajectoryPoint(positions=p, velocities=[0.0, 0.0], accelerations=[0.0, 0.0],
                             time_from_start=rospy.Duration(t)) for p, t in points])


class ArmSimTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_arm_sim')
        cls.lock = threading.Lock()
        cls.state = None
        rospy.Subscriber('/arm/arm_controller/state', JointTrajectoryControllerState, cls.on_state, queue_size=10)
        rospy.wait_for_service('/arm/controller_manager/list_controllers', WALL_TIMEOUT)
        lc = rospy.ServiceProxy('/arm/controller_manager/list_controllers', ListControllers)
        cls.wait('both controllers running', lambda: sum(c.state == 'running' for c in lc().controller) == 2)
        cls.client = actionlib.SimpleActionClient('/arm/arm_controller/follow_joint_trajectory',
                                                  FollowJointTrajectoryAction)
        cls.wait('the action server', lambda: cls.client.wait_for_server(rospy.Duration(0.1)))
        cls.command = rospy.Publisher('/arm/arm_controller/command', JointTrajectory, queue_size=1)
        cls.wait('the state topic', lambda: cls.state is not None)
        cls.wait('a subscriber of the command topic', lambda: cls.command.get_num_connections() > 0)

    @classmethod
    def on_state(cls, msg):
        with cls.lock:
            cls.state = msg

    @classmethod
    def wait(cls, what, cond):
        end = time.monotonic() + WALL_TIMEOUT
        while not cond():
            if rospy.is_shutdown() or time.monotonic() > end:
                raise AssertionError('timed out (%.0f s wall) waiting for %s' % (WALL_TIMEOUT, what))
            time.sleep(0.02)

    def actual(self):
        with self.lock:
            return list(self.state.actual.positions), list(self.state.actual.velocities)

    def run_goal(self, goal):
        self.client.send_goal(goal)
        # the terminal status can arrive before the result message: wait for both
        self.wait('an action result', lambda: self.client.get_state() in TERMINAL and
                  self.client.get_result() is not None)
        return self.client.get_state(), self.client.get_result()

    def settle(self):
        self.wait('the arm at rest', lambda: max(abs(v) for v in self.actual()[1]) < 0.05)

    def test_1_goal_reaches_the_end(self):
        state, result = self.run_goal(FollowJointTrajectoryGoal(
            trajectory=traj([([0.6, -0.4], 1.5), ([1.0, 0.5], 3.0)])))
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        self.assertEqual(FollowJointTrajectoryResult.SUCCESSFUL, result.error_code)
        self.settle()
        pos, _ = self.actual()
        self.assertAlmostEqual(1.0, pos[0], delta=0.03)
        self.assertAlmostEqual(0.5, pos[1], delta=0.03)

    def test_2_path_tolerance_violated(self):
        goal = FollowJointTrajectoryGoal(trajectory=traj([([-0.5, 0.0], 1.0)]),
                                         path_tolerance=[JointTolerance(name='shoulder', position=1e-4)])
        state, result = self.run_goal(goal)
        self.assertEqual(GoalStatus.ABORTED, state)
        self.assertEqual(FollowJointTrajectoryResult.PATH_TOLERANCE_VIOLATED, result.error_code)

    def test_3_topic_and_cancel(self):
        self.command.publish(traj([([0.0, 0.0], 2.0)]))
        rospy.sleep(3.0)  # sim time
        self.settle()
        pos, _ = self.actual()
        self.assertAlmostEqual(0.0, pos[0], delta=0.03)
        self.assertAlmostEqual(0.0, pos[1], delta=0.03)
        self.client.send_goal(FollowJointTrajectoryGoal(trajectory=traj([([2.0, 0.0], 4.0)])))
        self.wait('motion', lambda: self.actual()[0][0] > 0.3)
        self.client.cancel_goal()
        self.wait('an action result', lambda: self.client.get_state() in TERMINAL)
        self.assertEqual(GoalStatus.PREEMPTED, self.client.get_state())
        rospy.sleep(1.0)
        self.settle()
        pos, _ = self.actual()
        self.assertGreater(pos[0], 0.3)
        self.assertLess(pos[0], 1.8)


if __name__ == '__main__':
    rostest.rosrun('joint_trajectory_controller', 'jtc_arm_sim', ArmSimTest)
