"""Rotations, written once for every package that needs them (amcl, gmapping, costmap_2d,
base_local_planner, move_base, the benches; imu_filter_madgwick, robot_localization, ode_sim):
the yaw of a quaternion, the quaternion of a yaw, the quaternion of roll, pitch and yaw.
Plain arithmetic on anything with x, y, z, w fields
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


def quaternion_wxyz(roll, pitch, yaw):
    """(w, x, y, z) of fixed-axis roll about X, then pitch about Y, then yaw about Z (the URDF /
    SDF / tf convention): tf's quaternion_from_euler(roll, pitch, yaw), w first."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy)
