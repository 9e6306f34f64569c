"""The one module between ROS messages and the core: Grid <-> nav_msgs/OccupancyGrid."""
import numpy as np
from geometry_msgs.msg import Quaternion
from nav_msgs.msg import MapMetaData, OccupancyGrid
from nav_msgs.srv import GetMap, GetMapRequest, GetMapResponse
from rospy.numpy_msg import numpy_msg

from course_runtime.geometry import yaw_of, yaw_quaternion
from map_server.grid import Grid


# int8[] maps of millions of cells: serialise them from NumPy in one copy (same md5 and wire format)
NumpyOccupancyGrid = numpy_msg(OccupancyGrid)
NumpyGetMapResponse = numpy_msg(GetMapResponse)


class NumpyGetMap(object):
    """nav_msgs/GetMap whose response map serialises from NumPy (same type and md5 on the wire)."""
    _type = GetMap._type
    _md5sum = GetMap._md5sum
    _request_class = GetMapRequest
    _response_class = NumpyGetMapResponse


def grid_to_msg(grid, frame_id, stamp):
    """Grid -> OccupancyGrid (header stamped, info.map_load_time = stamp); data is an int8 array."""
    msg = NumpyOccupancyGrid()
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp
    msg.info = grid_metadata(grid, stamp)
    msg.data = np.ascontiguousarray(grid.data, dtype=np.int8).ravel()
    return msg


def grid_metadata(grid, stamp):
    info = MapMetaData()
    info.map_load_time = stamp
    info.resolution = grid.resolution
    info.width, info.height = grid.width, grid.height
    info.origin.position.x, info.origin.position.y = grid.origin[0], grid.origin[1]
    info.origin.orientation = Quaternion(*yaw_quaternion(grid.origin[2]))
    return info


def msg_to_grid(msg):
    """OccupancyGrid -> Grid (yaw taken from the origin quaternion)."""
    info = msg.info
    data = msg.data
    if isinstance(data, (bytes, bytearray)):
        arr = np.frombuffer(data, dtype=np.int8)
    else:
        arr = np.asarray(data, dtype=np.int8)
    origin = (info.origin.position.x, info.origin.position.y, yaw_of(info.origin.orientation))
    return Grid(info.width, info.height, info.resolution, origin, arr.copy())
