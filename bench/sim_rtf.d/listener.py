#!/usr/bin/env python3
"""Subscribes to the bench robot's sensors (plugins publish only while subscribed, as in Gazebo),
drives it in a slow circle, and when told to stop (SIGINT) prints per topic, as JSON: the
messages received, the first and last header stamps and the number of distinct stamps."""
import json
import signal
import sys

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, LaserScan

stamps = {'scan': [], 'imu': [], 'odom': []}


def recorder(key):
    def cb(msg):
        stamps[key].append(msg.header.stamp.to_nsec())
    return cb


def main():
    rospy.init_node('sim_rtf_listener', disable_signals=True)
    # queues large enough that this process never drops: every loss counted is upstream
    rospy.Subscriber('/scan', LaserScan, recorder('scan'), queue_size=10000)
    rospy.Subscriber('/imu', Imu, recorder('imu'), queue_size=10000)
    rospy.Subscriber('/odom', Odometry, recorder('odom'), queue_size=10000)
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
    out = {}
    for k, v in stamps.items():
        out[k] = {'received': len(v), 'first': min(v) * 1e-9 if v else 0.0,
                  'last': max(v) * 1e-9 if v else 0.0, 'distinct': len(set(v))}
    print(json.dumps(out), flush=True)
    rospy.signal_shutdown('done')
    sys.exit(0)


if __name__ == '__main__':
    main()
