#!/usr/bin/env python3
"""Self-study task of section 3.3.3: republish the turtle's position as a custom message.

Subscribes turtle1/pose (turtlesim/Pose) and publishes position2d
(my_super_robot_controller/Position2d: x, y) for every pose received.
Both names are relative, so the node also works inside a namespace (<group ns="...">).

  rosrun my_super_robot_controller position2d_node.py
  rostopic echo /position2d
"""
import rospy
from turtlesim.msg import Pose

from my_super_robot_controller.msg import Position2d


def to_position2d(pose):
    """The Position2d (x, y) of a turtlesim Pose."""
    return Position2d(x=pose.x, y=pose.y)


def main():
    rospy.init_node('position2d_node')
    pub = rospy.Publisher('position2d', Position2d, queue_size=10)
    rospy.Subscriber('turtle1/pose', Pose, lambda pose: pub.publish(to_position2d(pose)))
    rospy.loginfo('Republishing %s as %s', rospy.resolve_name('turtle1/pose'),
                  rospy.resolve_name('position2d'))
    rospy.spin()


if __name__ == '__main__':
    main()
