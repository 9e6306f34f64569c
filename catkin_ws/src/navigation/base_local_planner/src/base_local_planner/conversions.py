"""The one place where base_local_planner turns ROS messages into core data and back."""
import math

import numpy as np
import rospy
from geometry_msgs.msg import PoseStamped, Quaternion, Twist
from nav_msgs.msg import Path

from course_runtime.geometry import yaw_of, yaw_quaternion


def quaternion(yaw):
    return Quaternion(*yaw_quaternion(yaw))


def transform_to_xyyaw(t):
    """geometry_msgs/Transform -> (x, y, yaw) of a planar transform."""
    return t.translation.x, t.translation.y, yaw_of(t.rotation)


def plan_to_array(poses, tf_xyyaw=None):
    """list of PoseStamped -> (N, 3) x, y, yaw, optionally moved by a planar transform."""
    a = np.array([[p.pose.position.x, p.pose.position.y, yaw_of(p.pose.orientation)]
                  for p in poses], dtype=float).reshape(-1, 3)
    if tf_xyyaw is not None and len(a):
        tx, ty, tyaw = tf_xyyaw
        c, s = math.cos(tyaw), math.sin(tyaw)
        x = tx + c * a[:, 0] - s * a[:, 1]
        y = ty + s * a[:, 0] + c * a[:, 1]
        a = np.stack([x, y, a[:, 2] + tyaw], axis=1)
    return a


def array_to_path(arr, frame):
    msg = Path()
    msg.header.frame_id = frame
    msg.header.stamp = rospy.Time.now()
    for x, y, th in np.asarray(arr).reshape(-1, 3):
        p = PoseStamped()
        p.header = msg.header
        p.pose.position.x = float(x)
        p.pose.position.y = float(y)
        p.pose.orientation = quaternion(float(th))
        msg.poses.append(p)
    return msg


def twist(vx, vy, vth):
    t = Twist()
    t.linear.x = float(vx)
    t.linear.y = float(vy)
    t.angular.z = float(vth)
    return t


def odom_velocity(msg):
    tw = msg.twist.twist
    return tw.linear.x, tw.linear.y, tw.angular.z
