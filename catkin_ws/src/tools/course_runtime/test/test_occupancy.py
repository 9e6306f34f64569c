"""course_runtime.occupancy without a master: the one OccupancyGrid builder."""
import math

import numpy as np
import pytest
import rospy
from nav_msgs.msg import OccupancyGrid

from course_runtime.geometry import yaw_of
from course_runtime.occupancy import NumpyOccupancyGrid, map_metadata, occupancy_grid


def test_list_grid_rows_from_lowest_y():
    values = np.array([[0, 100, -1], [50, 0, 0]])
    msg = occupancy_grid(values, 0.25, (-1.0, 2.0), 'map', rospy.Time(3))
    assert type(msg) is OccupancyGrid
    assert msg.data == [0, 100, -1, 50, 0, 0]
    assert (msg.info.width, msg.info.height, msg.info.resolution) == (3, 2, 0.25)
    assert (msg.info.origin.position.x, msg.info.origin.position.y) == (-1.0, 2.0)
    assert msg.info.origin.orientation.w == 1.0 and msg.info.origin.orientation.z == 0.0
    assert msg.header.frame_id == 'map' and msg.header.stamp == rospy.Time(3)
    assert msg.info.map_load_time == rospy.Time(0)


def test_array_grid_with_yaw_and_load_time():
    values = np.zeros((4, 5), dtype=np.int8)
    msg = occupancy_grid(values, 0.05, (1.0, 2.0, math.pi / 2), 'odom', rospy.Time(7),
                         load_time=rospy.Time(7), as_array=True)
    assert isinstance(msg, NumpyOccupancyGrid)
    assert msg.data.dtype == np.int8 and msg.data.shape == (20,)
    assert yaw_of(msg.info.origin.orientation) == pytest.approx(math.pi / 2)
    assert msg.info.map_load_time == rospy.Time(7)
    buf = __import__('io').BytesIO()
    msg.serialize_numpy(buf, np)
    back = OccupancyGrid().deserialize(buf.getvalue())
    assert list(back.data) == [0] * 20 and (back.info.width, back.info.height) == (5, 4)


def test_metadata_and_bad_shape():
    info = map_metadata(0.1, (3, 2), (0.5, -0.5))
    assert (info.width, info.height) == (2, 3)
    with pytest.raises(ValueError, match='2-D'):
        occupancy_grid([1, 2, 3], 0.1, (0, 0), 'map', rospy.Time(0))
