#!/usr/bin/env python3
"""Drives the space scanner along waypoints in room B of the office (steering on the
simulator's ground truth, /gazebo/model_states) while the caller records a bag. Exits after
the last waypoint or DRIVE_LIMIT s of sim time."""
import math
import sys
import time

import rospy
from gazebo_msgs.msg import ModelStates
from geometry_msgs.msg import Twist

from course_runtime.geometry import yaw_of

WAYPOINTS = [(1.0, 0.0), (1.0, -1.6), (-1.0, -1.6), (-1.0, 0.9), (0.8, 0.9), (0.0, 0.0)]
DRIVE_LIMIT = 120.0
truth = None


def on_states(msg):
    global truth
    if 'robot' in msg.name:
        p = msg.pose[msg.name.index('robot')]
        q = p.orientation
        truth = (p.position.x, p.position.y, yaw_of(q))


def main():
    rospy.init_node('amcl_bench_driver')
    rospy.Subscriber('/gazebo/model_states', ModelStates, on_states, queue_size=1)
    pub = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=1)
    end = time.monotonic() + 600
    while (truth is None or pub.get_num_connections() == 0 or rospy.get_time() < 3.0) and time.monotonic() < end:
        time.sleep(0.1)
    if truth is None:
        sys.exit('amcl bench: no ground truth on /gazebo/model_states')
    rospy.sleep(1.0)
    t0 = rospy.get_time()
    for wx, wy in WAYPOINTS:
        while not rospy.is_shutdown() and rospy.get_time() - t0 < DRIVE_LIMIT:
            x, y, yaw = truth
            dist = math.hypot(wx - x, wy - y)
            if dist < 0.08:
                break
            err = (math.atan2(wy - y, wx - x) - yaw + math.pi) % (2 * math.pi) - math.pi
            cmd = Twist()
            cmd.angular.z = max(-0.4, min(0.4, 1.5 * err))
            cmd.linear.x = min(0.2, dist) if abs(err) < 0.3 else 0.0
            pub.publish(cmd)
            rospy.sleep(0.05)
    pub.publish(Twist())
    rospy.sleep(0.5)
    print('drive: %.1f s of sim time' % (rospy.get_time() - t0))


if __name__ == '__main__':
    main()
