#!/usr/bin/python3
"""Publish "hello world <time>" on `chatter` (std_msgs/String) ten times a second."""
import rospy
from std_msgs.msg import String


def talker():
    pub = rospy.Publisher('chatter', String, queue_size=10)
    rospy.init_node('talker', anonymous=True)
    rate = rospy.Rate(10)  # Hz
    while not rospy.is_shutdown():
        text = 'hello world %s' % rospy.get_time()
        rospy.loginfo(text)
        pub.publish(text)
        rate.sleep()


if __name__ == '__main__':
    try:
        talker()
    except rospy.ROSInterruptException:
        pass
