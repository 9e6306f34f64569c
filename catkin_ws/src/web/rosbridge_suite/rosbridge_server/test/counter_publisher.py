#!/usr/bin/python3
"""Test helper: publish `count` std_msgs/String messages "<seq>:<padding>" on /counter at
`rate` Hz (rospy timer on the ROS clock) once `subscribers` subscribers are connected."""
import sys
import time

import rospy
from std_msgs.msg import String


def main():
    count, rate, size, subscribers = (int(a) for a in sys.argv[1:5])
    rospy.init_node('counter_publisher')
    pub = rospy.Publisher('/counter', String, queue_size=count)
    deadline = time.monotonic() + 60
    while pub.get_num_connections() < subscribers and time.monotonic() < deadline:
        time.sleep(0.05)
    if pub.get_num_connections() < subscribers:
        sys.exit('counter_publisher: no subscriber on /counter within 60 s')
    pad = 'x' * size
    r = rospy.Rate(rate)
    for i in range(count):
        pub.publish(String('%d:%s' % (i, pad)))
        r.sleep()
    print('counter_publisher: published %d' % count, flush=True)
    time.sleep(1.0)


if __name__ == '__main__':
    main()
