"""nav_msgs/OccupancyGrid built once, for every package that publishes a grid: map_server's map
(and gmapping's, through map_server), costmap_2d's costmap, navfn's potential and the world
rasterised for the navigation tests and benches."""
import numpy as np
from geometry_msgs.msg import Quaternion
from nav_msgs.msg import MapMetaData, OccupancyGrid
from rospy.numpy_msg import numpy_msg

from course_runtime.geometry import yaw_quaternion

# int8[] maps of millions of cells: serialise them from NumPy in one copy (same md5 and wire format)
NumpyOccupancyGrid = numpy_msg(OccupancyGrid)


def map_metadata(resolution, shape, origin, load_time=None):
    """MapMetaData of a grid of shape (height, width) cells of `resolution` m whose cell (0, 0)
    has its lower-left corner at origin = (x, y) or (x, y, yaw) [m, m, rad] in the map frame;
    map_load_time = load_time when given (rospy.Time), else zero."""
    info = MapMetaData()
    if load_time is not None:
        info.map_load_time = load_time
    info.resolution = resolution
    info.height, info.width = shape
    info.origin.position.x, info.origin.position.y = origin[0], origin[1]
    info.origin.orientation = Quaternion(*yaw_quaternion(origin[2] if len(origin) > 2 else 0.0))
    return info


def occupancy_grid(values, resolution, origin, frame_id, stamp, load_time=None, as_array=False):
    """values: (height, width) cells, row 0 = lowest y, each -1 (unknown) or 0..100 -> an
    OccupancyGrid stamped `stamp` in `frame_id` (info as map_metadata). data is a list of ints,
    or with as_array=True an int8 array in a NumpyOccupancyGrid (same type on the wire)."""
    values = np.ascontiguousarray(values, dtype=np.int8)
    if values.ndim != 2:
        raise ValueError('occupancy grid values must be 2-D (height, width), got shape %s'
                         % (values.shape,))
    msg = NumpyOccupancyGrid() if as_array else OccupancyGrid()
    msg.header.frame_id = frame_id
    msg.header.stamp = stamp
    msg.info = map_metadata(resolution, values.shape, origin, load_time)
    msg.data = values.ravel() if as_array else values.ravel().tolist()
    return msg
