"""The one place where costmap_2d turns ROS messages into core data and back."""

import numpy as np
from geometry_msgs.msg import Point32, PolygonStamped
from map_msgs.msg import OccupancyGridUpdate

from course_runtime.geometry import yaw_of  # noqa: F401 (conversions.yaw_of)
from course_runtime.occupancy import occupancy_grid

from .costmap import cost_translation_table

_TABLE = cost_translation_table()


def transform_to_matrix(t):
    """geometry_msgs/Transform -> 4x4 homogeneous matrix."""
    q = t.rotation
    x, y, z, w = q.x, q.y, q.z, q.w
    m = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), t.translation.x],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), t.translation.y],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), t.translation.z],
        [0, 0, 0, 1]])
    return m


def apply_matrix(m, pts):
    pts = np.asarray(pts, dtype=float).reshape(-1, 3)
    return pts @ m[:3, :3].T + m[:3, 3]


def scan_to_points(scan, inf_is_valid=False):
    """LaserScan -> Nx3 points in the scan's frame (laser_geometry's projectLaser: readings
    outside [range_min, range_max) are dropped; with inf_is_valid, +inf becomes range_max)."""
    r = np.asarray(scan.ranges, dtype=float)
    a = scan.angle_min + np.arange(len(r)) * scan.angle_increment
    if inf_is_valid:
        r = np.where(np.isposinf(r), scan.range_max - 0.0001, r)
    ok = np.isfinite(r) & (r >= scan.range_min) & (r < scan.range_max)
    r, a = r[ok], a[ok]
    return np.stack([r * np.cos(a), r * np.sin(a), np.zeros_like(r)], axis=1)


_PC2_TYPES = {1: np.int8, 2: np.uint8, 3: np.int16, 4: np.uint16, 5: np.int32, 6: np.uint32,
              7: np.float32, 8: np.float64}


def cloud2_to_points(cloud):
    """PointCloud2 -> Nx3 finite points (x, y, z fields)."""
    fields = {f.name: f for f in cloud.fields}
    if not all(k in fields for k in 'xyz'):
        raise ValueError('PointCloud2 on %s has no x, y, z fields' % cloud.header.frame_id)
    n = cloud.width * cloud.height
    buf = np.frombuffer(bytes(cloud.data), dtype=np.uint8)
    out = np.empty((n, 3))
    endian = '>' if cloud.is_bigendian else '<'
    for i, k in enumerate('xyz'):
        f = fields[k]
        dt = np.dtype(_PC2_TYPES[f.datatype]).newbyteorder(endian)
        rows = buf[:n * cloud.point_step].reshape(n, cloud.point_step)
        out[:, i] = rows[:, f.offset:f.offset + dt.itemsize].copy().view(dt).ravel()
    return out[np.isfinite(out).all(axis=1)]


def cloud_to_points(cloud):
    """sensor_msgs/PointCloud -> Nx3."""
    return np.array([[p.x, p.y, p.z] for p in cloud.points], dtype=float).reshape(-1, 3)


def map_to_static_args(msg):
    """OccupancyGrid -> StaticLayer.set_map arguments (the origin's rotation is ignored, as
    the original does)."""
    info = msg.info
    return (info.width, info.height, info.resolution, info.origin.position.x,
            info.origin.position.y, np.asarray(msg.data, dtype=np.int16))


def costmap_to_grid(costmap, frame, stamp):
    return occupancy_grid(_TABLE[costmap.data], costmap.resolution,
                          (costmap.origin_x, costmap.origin_y), frame, stamp)


def costmap_to_update(costmap, frame, stamp):
    msg = OccupancyGridUpdate()
    msg.header.frame_id = frame
    msg.header.stamp = stamp
    msg.x = 0
    msg.y = 0
    msg.width = costmap.size_x
    msg.height = costmap.size_y
    msg.data = _TABLE[costmap.data].ravel().tolist()
    return msg


def footprint_to_polygon(points, frame, stamp):
    msg = PolygonStamped()
    msg.header.frame_id = frame
    msg.header.stamp = stamp
    msg.polygon.points = [Point32(x=float(x), y=float(y), z=0.0) for x, y in points]
    return msg
