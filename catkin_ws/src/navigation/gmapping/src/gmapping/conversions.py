"""The one module between ROS messages and the SLAM core: LaserScan -> beams, TF -> 2D poses,
the best particle's grid -> OccupancyGrid, map->odom as a TransformStamped."""
import math

import numpy as np
from geometry_msgs.msg import TransformStamped

from course_runtime.geometry import yaw_of
from map_server.conversions import grid_to_msg
from map_server.grid import Grid


def up_z(q):
    """z component of the frame's rotated z axis (1: upright, -1: upside down)."""
    return 1.0 - 2.0 * (q.x * q.x + q.y * q.y)


def transform_to_pose(t):
    """geometry_msgs/Transform -> (x, y, yaw)."""
    return np.array([t.translation.x, t.translation.y, yaw_of(t.rotation)])


def scan_beams(scan, upside_down=False):
    """LaserScan -> (ranges float64 (n,), angles float64 (n,)) in the laser's planar frame."""
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    angles = scan.angle_min + scan.angle_increment * np.arange(len(ranges))
    if upside_down:
        angles = -angles
    return ranges, angles


def compose(a, b):
    """2D pose composition a ⊕ b."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return np.array([a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1],
                     math.atan2(math.sin(a[2] + b[2]), math.cos(a[2] + b[2]))])


def inverse(a):
    c, s = math.cos(a[2]), math.sin(a[2])
    return np.array([-c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2]])


def map_to_odom(map_laser, odom_laser):
    """The map->odom correction: the laser's pose in the map composed with the inverse of its
    pose in odom."""
    return compose(map_laser, inverse(odom_laser))


def transform_msg(pose, parent, child, stamp):
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id, t.header.stamp = parent, child, stamp
    t.transform.translation.x, t.transform.translation.y = float(pose[0]), float(pose[1])
    t.transform.rotation.z, t.transform.rotation.w = math.sin(pose[2] / 2.0), math.cos(pose[2] / 2.0)
    return t


def map_msg(occupancy, grid_origin, params, frame_id, stamp):
    """Best particle's grid pasted into the xmin..xmax map slam_gmapping publishes."""
    d = params.delta
    w = int(round((params.xmax - params.xmin) / d))
    h = int(round((params.ymax - params.ymin) / d))
    data = np.full((h, w), -1, dtype=np.int8)
    if occupancy is not None:
        ox = int(round((grid_origin[0] - params.xmin) / d))
        oy = int(round((grid_origin[1] - params.ymin) / d))
        gh, gw = occupancy.shape
        x0, y0 = max(ox, 0), max(oy, 0)
        x1, y1 = min(ox + gw, w), min(oy + gh, h)
        if x1 > x0 and y1 > y0:
            data[y0:y1, x0:x1] = occupancy[y0 - oy:y1 - oy, x0 - ox:x1 - ox]
    return grid_to_msg(Grid(w, h, d, (params.xmin, params.ymin, 0.0), data), frame_id, stamp)
