#!/usr/bin/env python3
"""Says hello on topic chatter once a second."""
import rospy
from std_msgs.msg import String

if __name__ == '__main__':
    rospy.init_node('node4')
    pub = rospy.Publisher('chatter', String, queue_size=10)
    rate = rospy.Rate(1)
    while not rospy.is_shutdown():
        pub.publish(String('hello from node4 at %.1f' % rospy.get_time()))
        rate.sleep()
