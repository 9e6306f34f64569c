#!/usr/bin/env python3
"""control_rtf's driver: drives the space scanner in a slow circle on CMD_VEL (argv[1]) and
subscribes to its odometry ODOM (argv[2]); prints 'ready' once connected and, on SIGINT, the
number of odometry messages as JSON."""
import json
import signal
import sys

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry


def main():
    cmd_topic, odom_topic = sys.argv[1], sys.argv[2]
    rospy.init_node('control_rtf_driver', disable_signals=True)
    count = [0]
    rospy.Subscriber(odom_topic, Odometry, lambda _m: count.__setitem__(0, count[0] + 1), queue_size=1000)
    pub = rospy.Publisher(cmd_topic, Twist, queue_size=1)
    t = Twist()
    t.linear.x = 0.2
    t.angular.z = 0.3
    stop = []
    signal.signal(signal.SIGINT, lambda *_: stop.append(1))
    print('ready', flush=True)
    import time
    while not stop:
        pub.publish(t)      # diff_drive_controller's cmd_vel_timeout: keep commanding (wall 20 Hz)
        time.sleep(0.05)
    print(json.dumps({'odom': count[0]}), flush=True)


if __name__ == '__main__':
    main()
