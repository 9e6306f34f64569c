#!/usr/bin/env python3
"""Subscribes to the bench robot's sensors (plugins publish only while subscribed, as in Gazebo),
drives it in a slow circle, and prints message counts as JSON when told to stop (SIGINT)."""
import json
import signal
import sys

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, LaserScan

counts = {'scan': 0, 'imu': 0, 'odom': 0}


def counter(key):
    def cb(_msg):
        counts[key] += 1
    return cb


def main():
    rospy.init_node('sim_rtf_listener', disable_signals=True)
    rospy.Subscriber('/scan', LaserScan, counter('scan'), queue_size=100)
    rospy.Subscriber('/imu', Imu, counter('imu'), queue_size=1000)
    rospy.Subscriber('/odom', Odometry, counter('odom'), queue_size=1000)
    pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1, latch=True)
    t = Twist()
    t.linear.x = 0.2
    t.angular.z = 0.3
    pub.publish(t)
    done = []
    signal.signal(signal.SIGINT, lambda *_: done.append(1))
    print('ready', flush=True)
    while not done:
        signal.pause()
    print(json.dumps(counts), flush=True)
    rospy.signal_shutdown('done')
    sys.exit(0)


if __name__ == '__main__':
    main()
