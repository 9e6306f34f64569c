#!/usr/bin/python3
"""Test helper: publish geometry_msgs/Point on `pt` at 30 Hz with x = sin, y = cos (period 4 s)."""
import math

import rospy
from geometry_msgs.msg import Point

if __name__ == '__main__':
    rospy.init_node('sine_publisher')
    pub = rospy.Publisher('pt', Point, queue_size=10)
    rate = rospy.Rate(30)
    t0 = rospy.get_time()
    while not rospy.is_shutdown():
        t = rospy.get_time() - t0
        w = 2 * math.pi * t / 4.0
        pub.publish(Point(x=math.sin(w), y=math.cos(w), z=0.0))
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
