#!/usr/bin/env python3
"""Listens to number1 and prints what it hears."""
import rospy
from std_msgs.msg import Int32


def callback(msg):
    rospy.loginfo('node3 heard %d', msg.data)


if __name__ == '__main__':
    rospy.init_node('node3')
    rospy.Subscriber('number1', Int32, callback)
    rospy.spin()
