"""The one place where ROS messages meet the EKF core's arrays and tuples."""
import math

import numpy as np
from nav_msgs.msg import Odometry
from geometry_msgs.msg import TransformStamped

from .ekf import X, Y, Z, ROLL, PITCH, YAW, VX, VYAW
from .sensors import quaternion_to_rpy, rpy_to_quaternion


def quat_tuple(q):
    return (q.w, q.x, q.y, q.z)


def pose_tuple(pose):
    """geometry_msgs/Pose -> ((x, y, z, roll, pitch, yaw), quaternion norm)."""
    q = quat_tuple(pose.orientation)
    n = math.sqrt(sum(c * c for c in q))
    rpy = quaternion_to_rpy(q) if n > 0.0 else (0.0, 0.0, 0.0)
    return (pose.position.x, pose.position.y, pose.position.z) + tuple(rpy), n


def twist_tuple(twist):
    return (twist.linear.x, twist.linear.y, twist.linear.z,
            twist.angular.x, twist.angular.y, twist.angular.z)


def vector_tuple(v):
    return (v.x, v.y, v.z)


def cov6(values):
    return np.asarray(values, float).reshape(6, 6)


def cov3(values):
    return np.asarray(values, float).reshape(3, 3)


def odometry(x, P, stamp, frame, child):
    msg = Odometry()
    msg.header.stamp = stamp
    msg.header.frame_id = frame
    msg.child_frame_id = child
    p = msg.pose.pose
    p.position.x, p.position.y, p.position.z = float(x[X]), float(x[Y]), float(x[Z])
    q = rpy_to_quaternion(x[ROLL], x[PITCH], x[YAW])
    p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z = q
    t = msg.twist.twist
    t.linear.x, t.linear.y, t.linear.z = (float(v) for v in x[VX:VX + 3])
    t.angular.x, t.angular.y, t.angular.z = (float(v) for v in x[VYAW - 2:VYAW + 1])
    msg.pose.covariance = [float(v) for v in P[0:6, 0:6].ravel()]
    msg.twist.covariance = [float(v) for v in P[6:12, 6:12].ravel()]
    return msg


def transform(odom_msg, invert=False, time_offset=None):
    t = TransformStamped()
    t.header.stamp = odom_msg.header.stamp + time_offset if time_offset else odom_msg.header.stamp
    p = odom_msg.pose.pose
    if not invert:
        t.header.frame_id, t.child_frame_id = odom_msg.header.frame_id, odom_msg.child_frame_id
        t.transform.translation.x = p.position.x
        t.transform.translation.y = p.position.y
        t.transform.translation.z = p.position.z
        t.transform.rotation = p.orientation
        return t
    # inverse: base_link -> world
    from .sensors import _rot
    q = quat_tuple(p.orientation)
    R = _rot(*quaternion_to_rpy(q))
    tr = -R.T @ np.array([p.position.x, p.position.y, p.position.z])
    t.header.frame_id, t.child_frame_id = odom_msg.child_frame_id, odom_msg.header.frame_id
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = (float(v) for v in tr)
    t.transform.rotation.w, t.transform.rotation.x = q[0], -q[1]
    t.transform.rotation.y, t.transform.rotation.z = -q[2], -q[3]
    return t


def rotation_matrix(q):
    """3x3 matrix of a geometry_msgs/Quaternion."""
    from .sensors import _rot
    return _rot(*quaternion_to_rpy(quat_tuple(q)))


def matrix_rpy(R):
    from .sensors import _rpy
    return _rpy(R)
