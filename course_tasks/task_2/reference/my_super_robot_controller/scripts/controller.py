#!/usr/bin/env python3
"""The chapter's final controller, written to run in any namespace (section 3.4).

Keeps the turtle away from all four walls: straight ahead at ~speed in the middle of the
field, slower and turning when closer than 2 m to a wall. Also republishes the turtle's
position as my_super_robot_controller/Position2d.

Only relative names are used, so `<group ns="ns1">` moves everything to /ns1/...:
  sub  turtle1/pose      turtlesim/Pose
  pub  turtle1/cmd_vel   geometry_msgs/Twist
  pub  position2d        my_super_robot_controller/Position2d
Private parameter:
  ~speed  (float, m/s, default 2.0, must be > 0): forward speed in the middle of the field
"""
import math
import sys

import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

from my_super_robot_controller.msg import Position2d

MARGIN = 2.0        # m: closer to a wall than this -> turn
FIELD = 11.088889   # m: side of the turtlesim field
TURN_RATE = 1.4     # rad/s while turning


def near_wall(x, y, margin=MARGIN, field=FIELD):
    """True when (x, y) is closer than `margin` to any wall of the field."""
    return not (margin <= x <= field - margin and margin <= y <= field - margin)


def compute_cmd(x, y, speed):
    """(linear m/s, angular rad/s) for a turtle at (x, y): turn near walls, else go straight."""
    if near_wall(x, y):
        return speed / 2.0, TURN_RATE
    return speed, 0.0


def check_speed(value):
    """The ~speed parameter as a float; ValueError with a readable reason when it is bad."""
    try:
        speed = float(value)
    except (TypeError, ValueError):
        raise ValueError('parameter ~speed must be a number, got %r' % (value,))
    if not math.isfinite(speed) or speed <= 0.0:
        raise ValueError('parameter ~speed must be a positive number (m/s), got %r' % (value,))
    return speed


class Controller:
    def __init__(self, speed):
        self.speed = speed
        self.cmd_pub = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=10)
        self.pos_pub = rospy.Publisher('position2d', Position2d, queue_size=10)
        self.pose_sub = rospy.Subscriber('turtle1/pose', Pose, self.pose_callback, queue_size=1)

    def pose_callback(self, pose):
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = compute_cmd(pose.x, pose.y, self.speed)
        self.cmd_pub.publish(cmd)
        self.pos_pub.publish(Position2d(x=pose.x, y=pose.y))


def main():
    rospy.init_node('controller')
    try:
        speed = check_speed(rospy.get_param('~speed', 2.0))
    except ValueError as e:
        sys.exit('%s: %s' % (rospy.get_name(), e))
    Controller(speed)
    rospy.loginfo('%s: driving turtle %s at %.2f m/s', rospy.get_name(),
                  rospy.resolve_name('turtle1'), speed)
    rospy.spin()


if __name__ == '__main__':
    main()
