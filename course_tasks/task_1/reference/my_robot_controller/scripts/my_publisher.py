#!/usr/bin/env python3
"""Publisher of practical work 1 (the textbook's "talker", extended with a Twist).

Publishes, 10 times a second:
  * chatter  (std_msgs/String)      "hello world <time>";
  * cmd_vel  (geometry_msgs/Twist)  linear.x = 1.0 (drive forward).

`cmd_vel` is a relative name. turtlesim listens on /turtle1/cmd_vel, so to drive the
turtle remap the topic when starting the node:
  rosrun my_robot_controller my_publisher.py cmd_vel:=/turtle1/cmd_vel
"""
import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import String


def make_greeting(stamp):
    """The text sent on `chatter` at time `stamp` (seconds)."""
    return 'hello world %s' % stamp


def make_forward_twist(speed=1.0):
    """A Twist that drives straight ahead at `speed` m/s."""
    msg = Twist()
    msg.linear.x = speed
    return msg


def talker():
    pub = rospy.Publisher('chatter', String, queue_size=10)
    cmd_pub = rospy.Publisher('cmd_vel', Twist, queue_size=10)
    rospy.init_node('talker', anonymous=True)
    rate = rospy.Rate(10)  # 10 Hz
    while not rospy.is_shutdown():
        hello_str = make_greeting(rospy.get_time())
        rospy.loginfo(hello_str)
        pub.publish(hello_str)
        cmd_pub.publish(make_forward_twist())
        rate.sleep()


if __name__ == '__main__':
    try:
        talker()
    except rospy.ROSInterruptException:
        pass
