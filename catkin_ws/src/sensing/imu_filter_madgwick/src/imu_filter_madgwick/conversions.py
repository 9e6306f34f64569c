"""The one place where ROS messages meet the filter core's tuples."""
from geometry_msgs.msg import TransformStamped, Vector3Stamped, PoseStamped

from .filter import quat_to_rpy, quat_conj


def imu_vectors(msg):
    a, w = msg.linear_acceleration, msg.angular_velocity
    return (w.x, w.y, w.z), (a.x, a.y, a.z)


def mag_vector(msg):
    m = msg.magnetic_field
    return (m.x, m.y, m.z)


def fill_imu(msg, result):
    """msg (a copy of the input) gets the filtered orientation and covariance."""
    q = result.orientation
    o = msg.orientation
    o.w, o.x, o.y, o.z = q
    msg.orientation_covariance = list(result.covariance)
    la = result.linear_acceleration
    msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = la
    return msg


def transform(header, fixed_frame, q, reverse):
    t = TransformStamped()
    t.header.stamp = header.stamp
    if reverse:
        t.header.frame_id, t.child_frame_id = header.frame_id, fixed_frame
        q = quat_conj(q)
    else:
        t.header.frame_id, t.child_frame_id = fixed_frame, header.frame_id
    r = t.transform.rotation
    r.w, r.x, r.y, r.z = q
    return t


def rpy_msg(header, q):
    v = Vector3Stamped()
    v.header = header
    v.vector.x, v.vector.y, v.vector.z = quat_to_rpy(q)
    return v


def pose_msg(header, fixed_frame, q, translation):
    p = PoseStamped()
    p.header.stamp = header.stamp
    p.header.frame_id = fixed_frame
    p.pose.position.x, p.pose.position.y, p.pose.position.z = translation
    o = p.pose.orientation
    o.w, o.x, o.y, o.z = q
    return p
