"""The one module between ROS messages and amcl's core: OccupancyGrid -> Map, LaserScan ->
LaserData, poses <-> messages."""

import numpy as np
from geometry_msgs.msg import Pose, PoseArray, PoseWithCovarianceStamped, Quaternion

from course_runtime.geometry import yaw_of, yaw_quaternion
from course_runtime.transforms import transform_stamped

from .map import Map
from .sensors import LaserData


def quaternion(yaw):
    return Quaternion(*yaw_quaternion(yaw))


def _rotate(q, v):
    """Rotate vector(s) v (..., 3) by quaternion q."""
    x, y, z, w = q.x, q.y, q.z, q.w
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    return v @ r.T


def map_from_msg(msg):
    """OccupancyGrid -> Map as amcl's convertMap: 0 free, 100 occupied, anything else unknown."""
    info = msg.info
    data = np.asarray(msg.data, dtype=np.int16)
    if data.size != info.width * info.height:
        raise ValueError('map data has %d cells, expected %d x %d' % (data.size, info.width, info.height))
    grid = data.reshape(info.height, info.width)
    cells = np.zeros(grid.shape, dtype=np.int8)
    cells[grid == 0] = -1
    cells[grid == 100] = 1
    return Map(cells, info.resolution, info.origin.position.x, info.origin.position.y)


def pose_from_transform(t):
    """TransformStamped -> (x, y, yaw)."""
    tr = t.transform
    return np.array([tr.translation.x, tr.translation.y, yaw_of(tr.rotation)])


def laser_data(scan, laser_in_base, min_range=-1.0, max_range=-1.0):
    """LaserScan + the laser's TransformStamped in the base frame -> LaserData with bearings in
    the base frame (an upside-down laser reverses them). As amcl: laser_min/max_range > 0
    override the scan's; readings at or below the minimum count as max range."""
    range_max = scan.range_max
    if max_range > 0:
        range_max = min(range_max, max_range) if range_max > 0 else max_range
    range_min = scan.range_min
    if min_range > 0:
        range_min = max(range_min, min_range)
    ranges = np.asarray(scan.ranges, dtype=float)
    ranges = np.where(ranges <= range_min, range_max, ranges)
    ranges = np.where(ranges > range_max, range_max, ranges)
    angles = scan.angle_min + scan.angle_increment * np.arange(len(ranges))
    q = laser_in_base.transform.rotation
    dirs = _rotate(q, np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1))
    bearings = np.arctan2(dirs[:, 1], dirs[:, 0])
    t = laser_in_base.transform.translation
    return LaserData(ranges, bearings, float(range_max), (t.x, t.y, 0.0))


def pose_msg(x, y, yaw):
    p = Pose()
    p.position.x, p.position.y = float(x), float(y)
    p.orientation = quaternion(float(yaw))
    return p


def pose_with_covariance(pose, cov, stamp, frame_id):
    """amcl_pose: mean of the best cluster, covariance of the whole set (x, y block and yaw)."""
    msg = PoseWithCovarianceStamped()
    msg.header.stamp = stamp
    msg.header.frame_id = frame_id
    msg.pose.pose = pose_msg(*pose)
    c = [0.0] * 36
    for i in range(2):
        for j in range(2):
            c[6 * i + j] = float(cov[i, j])
    c[35] = float(cov[2, 2])
    msg.pose.covariance = c
    return msg


def initial_pose_from_msg(msg):
    """PoseWithCovarianceStamped -> mean (3,), cov (3, 3)."""
    p = msg.pose.pose
    c = msg.pose.covariance
    cov = np.array([[c[0], c[1], 0.0], [c[6], c[7], 0.0], [0.0, 0.0, c[35]]])
    return np.array([p.position.x, p.position.y, yaw_of(p.orientation)]), cov


def pose_array(poses, stamp, frame_id):
    msg = PoseArray()
    msg.header.stamp = stamp
    msg.header.frame_id = frame_id
    msg.poses = [pose_msg(*p) for p in poses]
    return msg


def transform(pose, stamp, parent, child):
    """(x, y, yaw) pose -> TransformStamped parent -> child."""
    return transform_stamped(stamp, parent, child, (pose[0], pose[1], 0.0),
                             yaw_quaternion(float(pose[2])))
