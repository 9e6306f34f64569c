#!/usr/bin/python3
"""rostest check (navigation_office.test): the space scanner, driven by move_base with the
diploma's YAMLs, leaves room B through the door and reaches a goal in the corridor; the
costmaps and the plan are published; a goal inside a wall is aborted with the reason after
the recoveries. All waits are on sim time with generous limits."""
import math
import os
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
from nav_msgs.msg import OccupancyGrid, Path

from course_testing import world_map

WORLD = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                     '../../../space_scanner/space_scanner_simulation/worlds/office.world')


def goal_at(x, y, yaw=0.0):
    g = MoveBaseGoal()
    g.target_pose.header.frame_id = 'map'
    g.target_pose.header.stamp = rospy.Time.now()
    g.target_pose.pose.position.x = x
    g.target_pose.pose.position.y = y
    g.target_pose.pose.orientation.z = math.sin(yaw / 2)
    g.target_pose.pose.orientation.w = math.cos(yaw / 2)
    return g


class Latest:
    def __init__(self, topic, kind):
        self.msg = None
        self.count = 0
        self.sub = rospy.Subscriber(topic, kind, self.cb, queue_size=1)

    def cb(self, m):
        self.msg = m
        self.count += 1
        self.longest = max(getattr(self, 'longest', 0), len(getattr(m, 'poses', [])))


def wait_sim(pred, sim_seconds, what, wall_limit=240.0):
    import time
    t_end = None
    wall_end = time.monotonic() + wall_limit
    while not rospy.is_shutdown():
        if pred():
            return True
        now = rospy.Time.now()
        if t_end is None and now.to_sec() > 0:
            t_end = now + rospy.Duration(sim_seconds)
        if (t_end is not None and now > t_end) or time.monotonic() > wall_end:
            raise AssertionError('timed out after %.0f s of sim time waiting for %s'
                                 % (sim_seconds, what))
        time.sleep(0.05)
    raise AssertionError('shut down while waiting for %s' % what)


class NavigationOffice(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_navigation')
        cls.map_pub = rospy.Publisher('/map', OccupancyGrid, queue_size=1, latch=True)
        cls.map_pub.publish(world_map.occupancy_grid(WORLD))
        cls.global_costmap = Latest('/move_base/global_costmap/costmap', OccupancyGrid)
        cls.local_costmap = Latest('/move_base/local_costmap/costmap', OccupancyGrid)
        cls.plan = Latest('/move_base/NavfnROS/plan', Path)
        cls.cmd = Latest('/diffbot_controller/cmd_vel', Twist)
        cls.client = actionlib.SimpleActionClient('move_base', MoveBaseAction)
        if not cls.client.wait_for_server(rospy.Duration(180)):
            raise AssertionError('the move_base action server did not come up in 180 s')
        rospy.wait_for_service('/gazebo/get_model_state', 120)
        cls.model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        # the robot drops from z 0.85 onto its wheels: let it settle for 2 s of sim time
        wait_sim(lambda: rospy.Time.now().to_sec() > 3.0, 60, 'sim time 3 s')

    def robot_xy(self):
        s = self.model_state('robot', '')
        return s.pose.position.x, s.pose.position.y

    def test_1_reaches_goal_through_the_door(self):
        self.client.send_goal(goal_at(0.0, 3.0, math.pi / 2))
        wait_sim(lambda: self.client.get_state() not in (GoalStatus.PENDING, GoalStatus.ACTIVE),
                 90, 'the move_base result')
        state = self.client.get_state()
        self.assertEqual(state, GoalStatus.SUCCEEDED,
                         'goal (0, 3) not reached: state %d, %r'
                         % (state, self.client.get_goal_status_text()))
        self.assertEqual(self.client.get_goal_status_text(), 'Goal reached.')
        x, y = self.robot_xy()
        self.assertLess(math.hypot(x - 0.0, y - 3.0), 0.35,
                        'the robot stopped at (%.2f, %.2f), not near (0, 3)' % (x, y))
        # what move_base published meanwhile
        self.assertIsNotNone(self.global_costmap.msg, 'no /move_base/global_costmap/costmap')
        g = self.global_costmap.msg
        self.assertEqual(g.header.frame_id, 'map')
        self.assertTrue(100 in g.data, 'the global costmap has no lethal cell')
        self.assertIsNotNone(self.local_costmap.msg, 'no /move_base/local_costmap/costmap')
        self.assertEqual(self.local_costmap.msg.header.frame_id, 'odom')
        self.assertIsNotNone(self.plan.msg, 'no plan on /move_base/NavfnROS/plan')
        # the first plan spans the 3 m (later replans may start near the goal)
        self.assertGreater(self.plan.longest, 40, 'the longest plan had %d poses'
                           % self.plan.longest)
        self.assertGreater(self.cmd.count, 20, 'move_base sent few commands on '
                           '/diffbot_controller/cmd_vel')

    def test_2_goal_in_a_wall_is_aborted_with_the_reason(self):
        # the outer wall at y = -4: no plan, recoveries, then the original's abort text
        self.client.send_goal(goal_at(0.0, -4.0))
        wait_sim(lambda: self.client.get_state() not in (GoalStatus.PENDING, GoalStatus.ACTIVE),
                 120, 'the abort of a goal inside a wall')
        self.assertEqual(self.client.get_state(), GoalStatus.ABORTED)
        self.assertEqual(self.client.get_goal_status_text(),
                         'Failed to find a valid plan. Even after executing recovery behaviors.')

    def test_3_make_plan_and_clear_costmaps_services(self):
        from nav_msgs.srv import GetPlan, GetPlanRequest
        from std_srvs.srv import Empty
        rospy.wait_for_service('/move_base/make_plan', 30)
        req = GetPlanRequest()
        req.goal.header.frame_id = 'map'
        req.goal.pose.position.x, req.goal.pose.position.y = 0.0, -1.5   # back in room B
        req.goal.pose.orientation.w = 1.0
        plan = rospy.ServiceProxy('/move_base/make_plan', GetPlan)(req).plan
        self.assertEqual(plan.header.frame_id, 'map')
        self.assertGreater(len(plan.poses), 20, 'make_plan from the robot to (0, -1.5) is short')
        last = plan.poses[-1].pose.position
        self.assertAlmostEqual(last.x, 0.0, delta=0.05)
        self.assertAlmostEqual(last.y, -1.5, delta=0.05)
        rospy.wait_for_service('/move_base/clear_costmaps', 30)
        rospy.ServiceProxy('/move_base/clear_costmaps', Empty)()


if __name__ == '__main__':
    rostest.rosrun('move_base', 'check_navigation', NavigationOffice)
