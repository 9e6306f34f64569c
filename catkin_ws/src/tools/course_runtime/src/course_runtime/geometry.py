"""Planar rotations, written once for every package that needs them (amcl, gmapping,
costmap_2d, base_local_planner, move_base, the benches): the yaw of a quaternion and the
quaternion of a yaw. Plain arithmetic on anything with x, y, z, w fields
(geometry_msgs/Quaternion): Debian's tf.transformations gives the same numbers at ~150 times
the cost per call (a 4x4 numpy matrix), and the local planner calls it for every pose of every
plan."""
import math


def yaw_of(q):
    """The rotation about z (rad, in [-pi, pi]) of quaternion q: tf's euler_from_quaternion(q)[2]
    for a unit quaternion."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def yaw_quaternion(yaw):
    """(x, y, z, w) of the rotation by yaw about z: tf's quaternion_from_euler(0, 0, yaw)."""
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))
