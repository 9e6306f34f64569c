#!/usr/bin/python3
"""Subscribe to `chatter` (std_msgs/String) and log every message received."""
import rospy
from std_msgs.msg import String


def callback(msg):
    # The caller id is followed by "I heard" without a space, exactly as in the original tutorial.
    rospy.loginfo(rospy.get_caller_id() + 'I heard %s', msg.data)


def listener():
    # anonymous=True gives the node a unique name, so several listeners can run at once.
    rospy.init_node('listener', anonymous=True)
    rospy.Subscriber('chatter', String, callback)
    rospy.spin()


if __name__ == '__main__':
    listener()
