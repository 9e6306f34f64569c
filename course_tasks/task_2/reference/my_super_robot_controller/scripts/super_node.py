#!/usr/bin/env python3
"""The textbook's first controller for turtlesim (practical work 2, section 3.2).

Subscribes /turtle1/pose (turtlesim/Pose) and for every pose publishes a command on
/turtle1/cmd_vel (geometry_msgs/Twist): drive straight at 2 m/s in the middle of the
field, slow down to 1 m/s and turn at 1.4 rad/s when x is near the left or right wall.

  rosrun turtlesim turtlesim_node                     # in one terminal
  rosrun my_super_robot_controller super_node.py      # in another
"""
import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

X_MIN = 2.0   # m: closer to the left wall than this -> turn
X_MAX = 9.0   # m: closer to the right wall than this -> turn


def compute_cmd(x):
    """(linear m/s, angular rad/s) for a turtle at abscissa x (m)."""
    if x > X_MAX or x < X_MIN:
        return 1.0, 1.4
    return 2.0, 0.0


def pose_callback(pose):
    cmd = Twist()
    cmd.linear.x, cmd.angular.z = compute_cmd(pose.x)
    publisher.publish(cmd)
    rospy.loginfo_throttle(1.0, 'Super node sending new msg: linear %.1f, angular %.1f'
                           % (cmd.linear.x, cmd.angular.z))


if __name__ == '__main__':
    rospy.init_node('turtle_super_node')
    rospy.loginfo('Node started...')
    publisher = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=10)
    subscriber = rospy.Subscriber('/turtle1/pose', Pose, callback=pose_callback)
    rospy.spin()
