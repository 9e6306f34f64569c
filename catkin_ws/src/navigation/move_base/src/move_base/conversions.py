"""The one place where move_base builds and reads ROS messages."""
import math

import rospy
from geometry_msgs.msg import PoseStamped, Quaternion
from move_base_msgs.msg import MoveBaseActionGoal, MoveBaseGoal  # noqa: F401

from course_runtime.geometry import yaw_of, yaw_quaternion


def quaternion_valid(q):
    """The original's isQuaternionValid: finite, non-zero length, z axis up."""
    vals = (q.x, q.y, q.z, q.w)
    if not all(math.isfinite(v) for v in vals):
        rospy.logerr('Quaternion has nans or infs... discarding as a navigation goal')
        return False
    n = math.sqrt(sum(v * v for v in vals))
    if n < 1e-6:
        rospy.logerr('Quaternion has length close to zero... discarding as navigation goal')
        return False
    x, y, z, w = (v / n for v in vals)
    # z axis of the rotated frame: third column of the rotation matrix
    up = 1 - 2 * (x * x + y * y)
    if abs(up - 1) > 1e-3:
        rospy.logerr('Quaternion is invalid... for navigation the z-axis of the quaternion '
                     'must be close to vertical.')
        return False
    return True


def pose_stamped(frame, x, y, yaw):
    p = PoseStamped()
    p.header.frame_id = frame
    p.header.stamp = rospy.Time.now()
    p.pose.position.x = x
    p.pose.position.y = y
    p.pose.orientation = Quaternion(*yaw_quaternion(yaw))
    return p


def transform_pose(ps, t, frame):
    """A planar transform (TransformStamped) applied to a PoseStamped."""
    tr = t.transform
    tyaw = yaw_of(tr.rotation)
    c, s = math.cos(tyaw), math.sin(tyaw)
    x, y = ps.pose.position.x, ps.pose.position.y
    out = pose_stamped(frame, tr.translation.x + c * x - s * y,
                       tr.translation.y + s * x + c * y, yaw_of(ps.pose.orientation) + tyaw)
    out.header.stamp = ps.header.stamp
    return out


def distance(a, b):
    return math.hypot(a.pose.position.x - b.pose.position.x,
                      a.pose.position.y - b.pose.position.y)


def action_goal(pose):
    g = MoveBaseActionGoal()
    g.header.stamp = rospy.Time.now()
    g.goal.target_pose = pose
    return g
