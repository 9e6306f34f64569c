"""The one place where navfn builds ROS messages."""
import numpy as np
import rospy
from geometry_msgs.msg import PoseStamped, Quaternion
from nav_msgs.msg import Path

from course_runtime.occupancy import occupancy_grid


def frame(msg):
    return msg.header.frame_id.lstrip('/')


def pose_stamped(frame_id, x, y, orientation=None):
    p = PoseStamped()
    p.header.frame_id = frame_id
    p.header.stamp = rospy.Time.now()
    p.pose.position.x = float(x)
    p.pose.position.y = float(y)
    p.pose.orientation = orientation if orientation is not None else Quaternion(0, 0, 0, 1)
    return p


def path(poses, frame_id):
    msg = Path()
    msg.header.frame_id = frame_id
    msg.header.stamp = rospy.Time.now()
    msg.poses = list(poses)
    return msg


def potential_to_grid(pot, pot_high, res, ox, oy, frame_id):
    finite = pot < pot_high
    top = pot[finite].max() if finite.any() else 1.0
    vals = np.full(pot.shape, -1, dtype=np.int8)
    vals[finite] = (pot[finite] * 99.0 / max(top, 1e-9)).astype(np.int8)
    return occupancy_grid(vals, res, (ox, oy), frame_id, rospy.Time.now())
