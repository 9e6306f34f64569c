"""The one module between ROS messages and the core: Grid <-> nav_msgs/OccupancyGrid."""
import numpy as np
from nav_msgs.srv import GetMap, GetMapRequest, GetMapResponse
from rospy.numpy_msg import numpy_msg

from course_runtime.geometry import yaw_of
from course_runtime.occupancy import NumpyOccupancyGrid, map_metadata, occupancy_grid
from map_server.grid import Grid

__all__ = ['NumpyOccupancyGrid', 'NumpyGetMapResponse', 'NumpyGetMap', 'grid_to_msg',
           'grid_metadata', 'msg_to_grid']

# the map of the GetMap service serialises from NumPy like the topic's (same md5 and wire format)
NumpyGetMapResponse = numpy_msg(GetMapResponse)


class NumpyGetMap(object):
    """nav_msgs/GetMap whose response map serialises from NumPy (same type and md5 on the wire)."""
    _type = GetMap._type
    _md5sum = GetMap._md5sum
    _request_class = GetMapRequest
    _response_class = NumpyGetMapResponse


def grid_to_msg(grid, frame_id, stamp):
    """Grid -> OccupancyGrid (header stamped, info.map_load_time = stamp); data is an int8 array."""
    return occupancy_grid(grid.data, grid.resolution, grid.origin, frame_id, stamp,
                          load_time=stamp, as_array=True)


def grid_metadata(grid, stamp):
    return map_metadata(grid.resolution, (grid.height, grid.width), grid.origin, stamp)


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
