#!/usr/bin/env python3
"""Adds up everything that arrives on number2 and prints the running total."""
import rospy
from std_msgs.msg import Int32

total = 0


def callback(msg):
    global total
    total += msg.data
    rospy.loginfo('node5 total %d', total)


if __name__ == '__main__':
    rospy.init_node('node5')
    rospy.Subscriber('number2', Int32, callback)
    rospy.spin()
