#!/usr/bin/env python3
"""Subscriber of practical work 1 (the textbook's "listener").

Prints every std_msgs/String received on `chatter`:
  rosrun my_robot_controller my_subscriber.py
"""
import rospy
from std_msgs.msg import String


def callback(data):
    rospy.loginfo(rospy.get_caller_id() + ' I heard %s', data.data)


def listener():
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber('chatter', String, callback)
    rospy.spin()


if __name__ == '__main__':
    listener()
