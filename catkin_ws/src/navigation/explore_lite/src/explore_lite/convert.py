"""The one conversion between ROS messages and the frontier core."""
import numpy as np

from explore_lite.frontiers import Grid, occupancy_to_costmap


def grid_from_msg(msg):
    """nav_msgs/OccupancyGrid -> Grid (costmap costs, rows = y)."""
    info = msg.info
    data = np.asarray(msg.data, dtype=np.int16).reshape(info.height, info.width)
    return Grid(occupancy_to_costmap(data), info.resolution,
                (info.origin.position.x, info.origin.position.y))


def apply_update(grid, msg):
    """map_msgs/OccupancyGridUpdate applied in place to a Grid; False if it does not fit."""
    h, w = grid.costs.shape
    if msg.x < 0 or msg.y < 0 or msg.x + msg.width > w or msg.y + msg.height > h:
        return False
    patch = np.asarray(msg.data, dtype=np.int16).reshape(msg.height, msg.width)
    grid.costs[msg.y:msg.y + msg.height, msg.x:msg.x + msg.width] = occupancy_to_costmap(patch)
    return True


def frontier_markers(frontiers, frame, stamp, blacklisted):
    """visualization_msgs/MarkerArray as explore_lite's ~frontiers: the cells of each frontier
    (blue, red when blacklisted) and a sphere at its start sized by its cost rank."""
    from geometry_msgs.msg import Point
    from std_msgs.msg import ColorRGBA
    from visualization_msgs.msg import Marker, MarkerArray
    out = MarkerArray()
    clear = Marker()
    clear.action = 3   # DELETEALL
    clear.header.frame_id = frame
    out.markers.append(clear)
    for i, f in enumerate(frontiers):
        bad = f.centroid in blacklisted
        pts = Marker()
        pts.header.frame_id, pts.header.stamp = frame, stamp
        pts.ns, pts.id, pts.type, pts.action = 'frontiers', 2 * i, Marker.POINTS, Marker.ADD
        pts.scale.x = pts.scale.y = 0.1
        pts.pose.orientation.w = 1.0
        pts.color = ColorRGBA(1.0 if bad else 0.0, 0.0, 0.0 if bad else 1.0, 1.0)
        pts.points = [Point(x, y, 0.0) for x, y in f.points]
        ball = Marker()
        ball.header.frame_id, ball.header.stamp = frame, stamp
        ball.ns, ball.id, ball.type, ball.action = 'frontiers', 2 * i + 1, Marker.SPHERE, Marker.ADD
        ball.pose.position = Point(f.initial[0], f.initial[1], 0.0)
        ball.pose.orientation.w = 1.0
        s = 0.5 if i == 0 else 0.3
        ball.scale.x = ball.scale.y = ball.scale.z = s
        ball.color = ColorRGBA(0.0, 1.0, 0.0, 1.0)
        out.markers.append(pts)
        out.markers.append(ball)
    return out
