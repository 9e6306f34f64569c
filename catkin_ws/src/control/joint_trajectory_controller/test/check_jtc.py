#!/usr/bin/env python3
"""jtc.test: joint_trajectory_controller's ROS interface as an action client and a command-topic
publisher use it, on the fake robot's sim time: outcomes and error codes, trajectory replacement,
cancel with the stop ramp, wrapping, tolerances, partial goals, state topic rate."""
import math
import threading
import time
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (FollowJointTrajectoryAction, FollowJointTrajectoryGoal,
                              FollowJointTrajectoryResult, JointTolerance,
                              JointTrajectoryControllerState)
from control_msgs.srv import QueryTrajectoryState
from controller_manager_msgs.srv import ListControllers, SwitchController
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

WALL_TIMEOUT = 120.0   # hang guard only; every judgement is on sim time
EPS = 0.01
TERMINAL = (GoalStatus.PREEMPTED, GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.REJECTED,
            GoalStatus.RECALLED, GoalStatus.LOST)
R = FollowJointTrajectoryResult


def point(positions, t, velocities=None, accelerations=None):
    p = JointTrajectoryPoint(positions=list(positions), time_from_start=rospy.Duration(t))
    if velocities is not None:
        p.velocities = list(velocities)
    if accelerations is not None:
        p.accelerations = list(accelerations)
    return p


def trajectory(joints, points, stamp=None):
    traj = JointTrajectory(joint_names=list(joints), points=points)
    if stamp is not None:
        traj.header.stamp = stamp
    return traj


def goal_of(traj, **kw):
    return FollowJointTrajectoryGoal(trajectory=traj, **kw)


class JointTrajectoryControllerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_jtc')
        cls.lock = threading.Lock()
        cls.states = {}
        cls.history = {}
        for ctrl in ('arm_controller', 'vel_controller', 'eff_controller'):
            cls.history[ctrl] = []
            rospy.Subscriber('/%s/state' % ctrl, JointTrajectoryControllerState, cls.on_state, ctrl,
                             queue_size=100)
        rospy.wait_for_service('/controller_manager/list_controllers', WALL_TIMEOUT)
        lister = rospy.ServiceProxy('/controller_manager/list_controllers', ListControllers)
        cls.switch = rospy.ServiceProxy('/controller_manager/switch_controller', SwitchController)
        cls.wait_wall('every controller running', lambda: sum(
            c.state == 'running' for c in lister().controller) == 4)
        cls.clients = {}
        for ctrl in ('arm_controller', 'vel_controller', 'eff_controller'):
            for k in (1, 2):
                c = actionlib.SimpleActionClient('/%s/follow_joint_trajectory' % ctrl,
                                                 FollowJointTrajectoryAction)
                assert c.wait_for_server(rospy.Duration(0)) or True
                cls.clients[ctrl, k] = c
        cls.wait_wall('action servers', lambda: all(
            c.wait_for_server(rospy.Duration(0.1)) for c in cls.clients.values()))
        cls.command = rospy.Publisher('/arm_controller/command', JointTrajectory, queue_size=10)
        cls.query = rospy.ServiceProxy('/arm_controller/query_state', QueryTrajectoryState)
        cls.wait_wall('state of every controller', lambda: len(cls.states) == 3)
        cls.wait_wall('a subscriber of /arm_controller/command', lambda: cls.command.get_num_connections() > 0)

    @classmethod
    def on_state(cls, msg, ctrl):
        with cls.lock:
            cls.states[ctrl] = msg
            cls.history[ctrl].append(msg)

    @classmethod
    def wait_wall(cls, what, cond):
        end = time.monotonic() + WALL_TIMEOUT
        while not cond():
            if rospy.is_shutdown() or time.monotonic() > end:
                raise AssertionError('timed out (%.0f s wall) waiting for %s' % (WALL_TIMEOUT, what))
            time.sleep(0.02)

    def state(self, ctrl='arm_controller'):
        with self.lock:
            return self.states[ctrl]

    def result_of(self, client):
        # the status array can report the terminal state before the result message arrives
        # (seen: REJECTED with get_result() None on a loaded machine): wait for both
        self.wait_wall('an action result', lambda: client.get_state() in TERMINAL and
                       client.get_result() is not None)
        return client.get_state(), client.get_result()

    def run_goal(self, goal, ctrl='arm_controller'):
        client = self.clients[ctrl, 1]
        client.send_goal(goal)
        return self.result_of(client)

    def stopped(self, ctrl='arm_controller'):
        s = self.state(ctrl)
        return (all(abs(v) < EPS for v in s.actual.velocities) and
                all(abs(v) < EPS for v in s.desired.velocities))

    def home(self, ctrl='arm_controller', joints=('j1', 'j2')):
        state, result = self.run_goal(goal_of(trajectory(joints, [point([0.0] * len(joints), 1.0)])), ctrl)
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        self.wait_wall('%s stopped' % ctrl, lambda: self.stopped(ctrl))

    def setUp(self):
        self.home()

    # -- state topic and query_state ------------------------------------------------------------
    def test_state_and_query(self):
        s = self.state()
        self.assertEqual(['j1', 'j2'], list(s.joint_names))
        for field in ('positions', 'velocities', 'accelerations'):
            self.assertEqual(2, len(getattr(s.desired, field)))
        self.assertEqual(2, len(s.actual.positions))
        self.assertEqual(2, len(s.actual.velocities))
        self.assertEqual(0, len(s.actual.accelerations))
        self.assertEqual(2, len(s.error.positions))
        self.assertEqual(0, len(s.error.accelerations))
        # A linear trajectory (positions only) queried ahead of time; it starts 5 s (sim) from now,
        # so a message delayed by a loaded machine still arrives before it.
        start = rospy.Time.now() + rospy.Duration(5.0)
        self.command.publish(trajectory(['j1', 'j2'], [point([1.0, -1.0], 2.0)], stamp=start))
        self.wait_wall('the new trajectory', lambda: self.query(start + rospy.Duration(1.0)).position[0] > 0.1)
        resp = self.query(start + rospy.Duration(2.0))
        self.assertEqual(['j1', 'j2'], list(resp.name))
        self.assertAlmostEqual(1.0, resp.position[0], places=6)
        self.assertAlmostEqual(-1.0, resp.position[1], places=6)
        self.assertEqual(0.0, resp.acceleration[0])

    # -- refused goals ----------------------------------------------------------------------------
    def test_invalid_goals(self):
        home = trajectory(['j1', 'j2'], [point([0.0, 0.0], 1.0)])
        cases = []
        partial = trajectory(['j1'], [point([0.0], 1.0)])
        cases.append(('partial joints', goal_of(partial), R.INVALID_JOINTS))
        bad = trajectory(['bad_name', 'j2'], [point([0.0, 0.0], 1.0)])
        cases.append(('unknown joint', goal_of(bad), R.INVALID_JOINTS))
        bad = trajectory(['j1', 'j2'], [point([], 1.0)])
        cases.append(('no positions', goal_of(bad), R.INVALID_GOAL))
        bad = trajectory(['j1', 'j2'], [point([0.0], 1.0)])
        cases.append(('positions of one joint', goal_of(bad), R.INVALID_GOAL))
        bad = trajectory(['j1', 'j2'], [point([0.1, 0.0], 1.0), point([0.2, 0.0], 1.0)])
        cases.append(('times not increasing', goal_of(bad), R.INVALID_GOAL))
        cases.append(('empty goal', FollowJointTrajectoryGoal(), R.INVALID_JOINTS))
        old = trajectory(['j1', 'j2'], [point([0.5, 0.0], 1.0)], stamp=rospy.Time.now() - rospy.Duration(2.0))
        cases.append(('all points in the past', goal_of(old), R.INVALID_GOAL))
        for what, goal, code in cases:
            state, result = self.run_goal(goal)
            self.assertEqual(GoalStatus.REJECTED, state, what)
            self.assertEqual(code, result.error_code, what)
            self.assertTrue(result.error_string, what)
        self.assertTrue(home)

    # -- execution ---------------------------------------------------------------------------------
    def test_action_quintic_trajectory(self):
        pts = [point([math.pi / 4, 0.0], 1.0, [0.3, -0.3], [0.0, 0.0]),
               point([0.0, -math.pi / 4], 2.0, [0.0, 0.0], [0.0, 0.0]),
               point([-math.pi / 4, math.pi / 4], 3.0, [0.0, 0.0], [0.0, 0.0])]
        state, result = self.run_goal(goal_of(trajectory(['j1', 'j2'], pts)))
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        self.assertEqual(R.SUCCESSFUL, result.error_code)
        self.wait_wall('stop', self.stopped)
        s = self.state()
        for i in range(2):
            self.assertAlmostEqual(pts[-1].positions[i], s.desired.positions[i], delta=EPS)
            self.assertAlmostEqual(pts[-1].positions[i], s.actual.positions[i], delta=EPS)
            self.assertAlmostEqual(0.0, s.error.positions[i], delta=EPS)

    def test_joint_reordering(self):
        state, _ = self.run_goal(goal_of(trajectory(['j2', 'j1'], [point([0.5, -0.25], 1.0)])))
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        self.wait_wall('stop', self.stopped)  # the state message of the last sample may still be in flight
        s = self.state()
        self.assertAlmostEqual(-0.25, s.desired.positions[0], delta=EPS)
        self.assertAlmostEqual(0.5, s.desired.positions[1], delta=EPS)

    def test_topic_replaces_future_part(self):
        self.command.publish(trajectory(['j1', 'j2'], [point([1.0, 1.0], 2.0)]))
        self.wait_wall('execution', lambda: self.state().desired.positions[0] > 0.05)
        t_new = rospy.Time.now() + rospy.Duration(1.0)  # margin for a delayed message
        before = self.query(t_new - rospy.Duration(0.1)).position[0]
        self.command.publish(trajectory(['j1', 'j2'], [point([-0.5, 0.2], 1.5)], stamp=t_new))
        self.wait_wall('replacement', lambda: self.query(t_new + rospy.Duration(1.5)).position[0] < -0.4)
        # Until the new trajectory starts, the old one is followed unchanged.
        self.assertAlmostEqual(before, self.query(t_new - rospy.Duration(0.1)).position[0], places=6)
        self.wait_wall('the end of the new trajectory', lambda: rospy.Time.now() > t_new + rospy.Duration(1.6))
        self.wait_wall('stop', self.stopped)
        s = self.state()
        self.assertAlmostEqual(-0.5, s.actual.positions[0], delta=EPS)
        self.assertAlmostEqual(0.2, s.actual.positions[1], delta=EPS)

    def test_new_goal_or_topic_preempts_goal(self):
        long_traj = trajectory(['j1', 'j2'], [point([1.0, 1.0], 3.0)])
        c1, c2 = self.clients['arm_controller', 1], self.clients['arm_controller', 2]
        c1.send_goal(goal_of(long_traj))
        self.wait_wall('execution', lambda: self.state().desired.positions[0] > 0.05)
        c2.send_goal(goal_of(trajectory(['j1', 'j2'], [point([0.0, 0.0], 1.0)])))
        self.assertEqual(GoalStatus.PREEMPTED, self.result_of(c1)[0])
        self.assertEqual(GoalStatus.SUCCEEDED, self.result_of(c2)[0])

        c1.send_goal(goal_of(long_traj))
        self.wait_wall('execution', lambda: self.state().desired.positions[0] > 0.05)
        self.command.publish(trajectory(['j1', 'j2'], [point([0.0, 0.0], 1.0)]))
        self.assertEqual(GoalStatus.PREEMPTED, self.result_of(c1)[0])
        rospy.sleep(1.5)
        self.wait_wall('stop', self.stopped)
        self.assertAlmostEqual(0.0, self.state().actual.positions[0], delta=EPS)

    def test_old_goal_does_not_preempt(self):
        c1, c2 = self.clients['arm_controller', 1], self.clients['arm_controller', 2]
        c1.send_goal(goal_of(trajectory(['j1', 'j2'], [point([0.6, 0.0], 1.5)])))
        self.wait_wall('execution', lambda: self.state().desired.positions[0] > 0.05)
        stale = trajectory(['j1', 'j2'], [point([0.0, 0.5], 1.0)], stamp=rospy.Time.now() - rospy.Duration(1.5))
        c2.send_goal(goal_of(stale))
        self.assertEqual(GoalStatus.REJECTED, self.result_of(c2)[0])
        self.assertEqual(GoalStatus.SUCCEEDED, self.result_of(c1)[0])
        # the result may arrive before the state message of the last sample (the same race as
        # test_joint_reordering): wait for that message, then compare
        self.wait_wall('the final state', lambda: abs(self.state().desired.positions[0] - 0.6) < EPS)
        self.assertAlmostEqual(0.6, self.state().desired.positions[0], delta=EPS)

    def test_cancel_stops_with_ramp(self):
        c1 = self.clients['arm_controller', 1]
        c1.send_goal(goal_of(trajectory(['j1', 'j2'], [point([2.0, 0.0], 4.0)])))
        self.wait_wall('execution', lambda: self.state().desired.positions[0] > 0.3)
        with self.lock:
            mark = len(self.history['arm_controller'])
        c1.cancel_goal()
        self.assertEqual(GoalStatus.PREEMPTED, self.result_of(c1)[0])
        rospy.sleep(1.0)  # stop_trajectory_duration is 0.5 s
        self.wait_wall('stop', self.stopped)
        with self.lock:
            after = self.history['arm_controller'][mark:]
        # The ramp decelerates without reversing and stops short of the goal.
        self.assertTrue(all(m.desired.velocities[0] > -1e-6 for m in after))
        final = self.state().actual.positions[0]
        self.assertGreater(final, after[0].desired.positions[0])
        self.assertLess(final, 1.9)

    def test_empty_goal_and_empty_topic_stop(self):
        c1, c2 = self.clients['arm_controller', 1], self.clients['arm_controller', 2]
        c1.send_goal(goal_of(trajectory(['j1', 'j2'], [point([2.0, 0.0], 4.0)])))
        self.wait_wall('execution', lambda: self.state().desired.positions[0] > 0.3)
        c2.send_goal(goal_of(trajectory(['j1', 'j2'], [])))
        self.assertEqual(GoalStatus.PREEMPTED, self.result_of(c1)[0])
        self.assertEqual(GoalStatus.SUCCEEDED, self.result_of(c2)[0])
        self.wait_wall('stop', self.stopped)
        self.assertLess(self.state().actual.positions[0], 1.9)

        self.command.publish(trajectory(['j1', 'j2'], [point([0.0, 0.0], 4.0)]))
        self.wait_wall('execution', lambda: self.state().desired.positions[0] < 0.5)
        self.command.publish(JointTrajectory())
        rospy.sleep(1.0)
        self.wait_wall('stop', self.stopped)
        self.assertGreater(self.state().actual.positions[0], 0.1)

    def test_continuous_joint_wraps(self):
        g1 = goal_of(trajectory(['j1', 'j2'], [point([0.0, 0.5 * math.pi], 1.0)]))
        g2 = goal_of(trajectory(['j1', 'j2'], [point([0.0, -1.75 * math.pi], 1.0)]))
        self.assertEqual(GoalStatus.SUCCEEDED, self.run_goal(g1)[0])
        self.assertEqual(GoalStatus.SUCCEEDED, self.run_goal(g2)[0])
        self.wait_wall('stop', self.stopped)
        # -1.75 pi is 0.25 pi: a quarter turn back, not one and a quarter turns.
        self.assertAlmostEqual(0.25 * math.pi, self.state().desired.positions[1], delta=EPS)
        g3 = goal_of(trajectory(['j1', 'j2'], [point([0.0, 0.0], 1.0)]))
        self.assertEqual(GoalStatus.SUCCEEDED, self.run_goal(g3)[0])

    def test_hold_position_on_start(self):
        self.assertEqual(GoalStatus.SUCCEEDED, self.run_goal(goal_of(
            trajectory(['j1', 'j2'], [point([0.4, -0.3], 1.0)])))[0])
        self.assertTrue(self.switch([], ['arm_controller'], 2, False, 0.0).ok)
        self.assertTrue(self.switch(['arm_controller'], [], 2, False, 0.0).ok)
        with self.lock:
            mark = len(self.history['arm_controller'])
        self.wait_wall('states after restart', lambda: len(self.history['arm_controller']) > mark + 5)
        s = self.state()
        self.assertAlmostEqual(0.4, s.desired.positions[0], delta=EPS)
        self.assertAlmostEqual(-0.3, s.desired.positions[1], delta=EPS)
        self.assertAlmostEqual(0.4, s.actual.positions[0], delta=EPS)

    # -- tolerances (effort variant: PD-controlled unit inertia lags behind) --------------------
    def test_path_tolerance_violated(self):
        goal = goal_of(trajectory(['e1'], [point([1.0], 1.0)]),
                       path_tolerance=[JointTolerance(name='e1', position=0.001)])
        state, result = self.run_goal(goal, 'eff_controller')
        self.assertEqual(GoalStatus.ABORTED, state)
        self.assertEqual(R.PATH_TOLERANCE_VIOLATED, result.error_code)
        self.home('eff_controller', ('e1',))

    def test_goal_tolerance_violated(self):
        goal = goal_of(trajectory(['e1'], [point([1.0], 1.0)]),
                       path_tolerance=[JointTolerance(name='e1', position=-1.0, velocity=-1.0)],
                       goal_tolerance=[JointTolerance(name='e1', position=1e-6)],
                       goal_time_tolerance=rospy.Duration(0.05))
        state, result = self.run_goal(goal, 'eff_controller')
        self.assertEqual(GoalStatus.ABORTED, state)
        self.assertEqual(R.GOAL_TOLERANCE_VIOLATED, result.error_code)
        self.home('eff_controller', ('e1',))

    def test_effort_and_velocity_reach_goals(self):
        state, result = self.run_goal(goal_of(trajectory(['e1'], [point([0.8], 1.5)])), 'eff_controller')
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        self.wait_wall('eff_controller stopped', lambda: self.stopped('eff_controller'))
        self.assertAlmostEqual(0.8, self.state('eff_controller').actual.positions[0], delta=0.03)
        self.home('eff_controller', ('e1',))
        state, _ = self.run_goal(goal_of(trajectory(['v1', 'v2'], [point([0.5, -0.5], 1.5)])), 'vel_controller')
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        self.wait_wall('vel_controller stopped', lambda: self.stopped('vel_controller'))
        s = self.state('vel_controller')
        self.assertAlmostEqual(0.5, s.actual.positions[0], delta=0.03)
        self.assertAlmostEqual(-0.5, s.actual.positions[1], delta=0.03)

    def test_partial_joints_goal(self):
        self.home('vel_controller', ('v1', 'v2'))
        state, _ = self.run_goal(goal_of(trajectory(['v1', 'v2'], [point([0.3, 0.3], 1.0)])), 'vel_controller')
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        state, _ = self.run_goal(goal_of(trajectory(['v2'], [point([-0.4], 1.0)])), 'vel_controller')
        self.assertEqual(GoalStatus.SUCCEEDED, state)
        self.wait_wall('vel_controller stopped', lambda: self.stopped('vel_controller'))
        s = self.state('vel_controller')
        self.assertAlmostEqual(0.3, s.desired.positions[0], delta=1e-6)  # v1 kept its trajectory
        self.assertAlmostEqual(-0.4, s.desired.positions[1], delta=EPS)
        self.home('vel_controller', ('v1', 'v2'))

    # -- state_publish_rate, judged by the stamps (sim time) -----------------------------------
    def test_state_publish_rate(self):
        with self.lock:
            mark = len(self.history['arm_controller'])
        start = rospy.Time.now()
        self.wait_wall('4 s of sim time', lambda: rospy.Time.now() - start > rospy.Duration(4.0))
        with self.lock:
            msgs = self.history['arm_controller'][mark:]
        stamps = [m.header.stamp.to_sec() for m in msgs]
        rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        self.assertAlmostEqual(25.0, rate, delta=25.0 * 0.05)


if __name__ == '__main__':
    rostest.rosrun('joint_trajectory_controller', 'joint_trajectory_controller', JointTrajectoryControllerTest)
