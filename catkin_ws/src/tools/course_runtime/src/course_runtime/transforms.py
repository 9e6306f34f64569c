"""geometry_msgs/TransformStamped built once, for every package that broadcasts a transform
from plain numbers (amcl's map -> odom, ode_sim's odometry and link transforms)."""
from geometry_msgs.msg import TransformStamped


def transform_stamped(stamp, parent, child, translation, rotation):
    """parent -> child: translation (x, y, z) [m] and rotation (x, y, z, w) as floats, header
    stamped `stamp` (rospy.Time)."""
    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id = parent
    t.child_frame_id = child
    tr = t.transform.translation
    tr.x, tr.y, tr.z = (float(v) for v in translation)
    r = t.transform.rotation
    r.x, r.y, r.z, r.w = (float(v) for v in rotation)
    return t
