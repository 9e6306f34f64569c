#!/usr/bin/env python3
"""navigation_sim.test: navigation.launch sim:=true on the office's map. AMCL localizes the
robot (amcl_pose near the simulator's ground truth), move_base takes a goal 1.4 m away through
its action and reaches it (ground truth within the diploma's xy_goal_tolerance + a margin),
publishing a global plan."""
import math
import unittest

import actionlib
import rospy
import rostest
from course_testing import wait_for
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import PoseWithCovarianceStamped
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
from nav_msgs.msg import Path
from std_srvs.srv import Empty

WALL_TIMEOUT = 240.0


def wait(cond, what, timeout=WALL_TIMEOUT):
    wait_for(lambda: rospy.is_shutdown() or cond(), timeout, 0.1, what)
    assert not rospy.is_shutdown(), 'shut down while waiting for %s' % what
GOAL = (1.0, -1.0)


class NavigationSim(unittest.TestCase):
    def test_goal_reached(self):
        got = {}
        rospy.Subscriber('/amcl_pose', PoseWithCovarianceStamped, lambda m: got.__setitem__('amcl', m))
        rospy.Subscriber('/move_base/NavfnROS/plan', Path, lambda m: got.__setitem__('plan', m))
        rospy.wait_for_service('/gazebo/get_model_state', WALL_TIMEOUT)
        truth = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        client = actionlib.SimpleActionClient('move_base', MoveBaseAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(WALL_TIMEOUT)), 'no move_base action server')
        wait(lambda: 'amcl' in got, 'amcl_pose')
        goal = MoveBaseGoal()
        goal.target_pose.header.frame_id = 'map'
        goal.target_pose.header.stamp = rospy.Time.now()
        goal.target_pose.pose.position.x, goal.target_pose.pose.position.y = GOAL
        goal.target_pose.pose.orientation.w = 1.0
        client.send_goal(goal)
        wait(lambda: client.get_state() not in (0, 1), 'move_base to finish the goal')  # PENDING, ACTIVE
        self.assertEqual(client.get_state(), 3, 'goal state %d: %s' % (
            client.get_state(), client.get_goal_status_text()))
        p = truth(model_name='robot').pose.position
        self.assertLess(math.hypot(p.x - GOAL[0], p.y - GOAL[1]), 0.35,
                        'ground truth (%.2f, %.2f) vs goal %s' % (p.x, p.y, GOAL))
        # amcl publishes a pose only after a filter update (every update_min_d of travel): at
        # rest a no-motion update gives one for where the robot stands now
        rospy.wait_for_service('/request_nomotion_update', WALL_TIMEOUT)
        stamp = got['amcl'].header.stamp
        rospy.ServiceProxy('/request_nomotion_update', Empty)()
        wait(lambda: got['amcl'].header.stamp > stamp, 'an /amcl_pose after request_nomotion_update')
        p = truth(model_name='robot').pose.position
        a = got['amcl'].pose.pose.position
        self.assertLess(math.hypot(a.x - p.x, a.y - p.y), 0.2,
                        'amcl (%.2f, %.2f) vs ground truth (%.2f, %.2f)' % (a.x, a.y, p.x, p.y))
        self.assertIn('plan', got, 'no global plan on /move_base/NavfnROS/plan')


if __name__ == '__main__':
    rospy.init_node('check', anonymous=True)
    rostest.rosrun('space_scanner_bringup', 'check_navigation_sim', NavigationSim)
