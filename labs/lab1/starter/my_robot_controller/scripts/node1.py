#!/usr/bin/env python3
"""Sends a random integer on topic number1 twice a second."""
import random

import rospy
from std_msgs.msg import Int32

if __name__ == '__main__':
    rospy.init_node('node1')
    pub = rospy.Publisher('number1', Int32, queue_size=10)
    rate = rospy.Rate(2)
    while not rospy.is_shutdown():
        pub.publish(Int32(random.randint(1, 100)))
        rate.sleep()
