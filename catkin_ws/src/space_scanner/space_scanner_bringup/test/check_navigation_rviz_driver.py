#!/usr/bin/python3
"""Goal driver of test_navigation_rviz.py (a node of its own, so the pytest process stays free
of rospy): waits for AMCL and for RViz to be connected to the global plan's topic, sends one
move_base goal, prints one JSON line per event on stdout:
  {"kind": "plan", "poses": [[x, y], ...]}             every global plan (map frame)
  {"kind": "result", "state": N, "text": ..., "truth": [x, y], "amcl": [x, y]}
then waits for the flag file argv[3] (the test's screenshots are done) or 120 s.
argv: goal x, goal y, flag file."""
import json
import os
import sys
import time
import xmlrpc.client

import actionlib
import rosgraph
import rospy
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import PoseWithCovarianceStamped
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
from nav_msgs.msg import Path
from std_srvs.srv import Empty

WALL_TIMEOUT = 240.0
PLAN = '/move_base/NavfnROS/plan'


def emit(**kw):
    sys.stdout.write(json.dumps(kw) + '\n')
    sys.stdout.flush()


def wait(cond, what, timeout=WALL_TIMEOUT):
    deadline = time.monotonic() + timeout
    while not cond():
        if rospy.is_shutdown() or time.monotonic() > deadline:
            emit(kind='error', text='timed out after %.0f s waiting for %s' % (timeout, what))
            sys.exit(1)
        time.sleep(0.1)


def connected(node, topic, peer):
    """True when `node` has a live connection on `topic` with node `peer` (its XML-RPC
    getBusInfo, as `rosnode info` shows it)."""
    try:
        uri = rosgraph.Master(rospy.get_name()).lookupNode(node)
        _, _, info = xmlrpc.client.ServerProxy(uri).getBusInfo(rospy.get_name())
    except Exception:   # not up yet
        return False
    return any(len(c) > 5 and c[1] == peer and c[4] == topic and c[5] for c in info)


def main():
    gx, gy, flag = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
    rospy.init_node('navigation_rviz_driver', anonymous=True, disable_signals=True)
    got = {}
    rospy.Subscriber('/amcl_pose', PoseWithCovarianceStamped, lambda m: got.__setitem__('amcl', m))
    rospy.Subscriber(PLAN, Path, lambda m: emit(
        kind='plan', poses=[[p.pose.position.x, p.pose.position.y] for p in m.poses]))
    rospy.wait_for_service('/gazebo/get_model_state', WALL_TIMEOUT)
    truth = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
    client = actionlib.SimpleActionClient('move_base', MoveBaseAction)
    if not client.wait_for_server(rospy.Duration(WALL_TIMEOUT)):
        emit(kind='error', text='no move_base action server after %.0f s' % WALL_TIMEOUT)
        return 1
    wait(lambda: 'amcl' in got, 'amcl_pose')
    # a user sends the goal from RViz, once it is up: move_base publishes the global plan once
    # per goal (planner_frequency 0, not latched), so an RViz still starting on a loaded
    # machine missed it and showed none (a stress round)
    wait(lambda: connected('/move_base', PLAN, '/rviz'), 'RViz connected to ' + PLAN)
    goal = MoveBaseGoal()
    goal.target_pose.header.frame_id = 'map'
    goal.target_pose.header.stamp = rospy.Time.now()
    goal.target_pose.pose.position.x, goal.target_pose.pose.position.y = gx, gy
    goal.target_pose.pose.orientation.w = 1.0
    client.send_goal(goal)
    emit(kind='sent', goal=[gx, gy])
    # PENDING, ACTIVE
    wait(lambda: client.get_state() not in (0, 1), 'move_base to finish the goal')
    # amcl publishes a pose only after a filter update (every update_min_d of travel): at rest
    # a no-motion update gives one for where the robot stands now
    rospy.wait_for_service('/request_nomotion_update', WALL_TIMEOUT)
    stamp = got['amcl'].header.stamp
    rospy.ServiceProxy('/request_nomotion_update', Empty)()
    wait(lambda: got['amcl'].header.stamp > stamp, 'an /amcl_pose after request_nomotion_update')
    p = truth(model_name='robot').pose.position
    a = got['amcl'].pose.pose.position
    emit(kind='result', state=client.get_state(), text=client.get_goal_status_text(),
         truth=[p.x, p.y], amcl=[a.x, a.y])
    wait(lambda: os.path.exists(flag), 'the test to finish its screenshots', 120.0)
    return 0


if __name__ == '__main__':
    sys.exit(main())
