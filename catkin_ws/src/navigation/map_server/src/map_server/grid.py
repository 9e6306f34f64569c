"""A plain occupancy grid, the shape of nav_msgs/OccupancyGrid without ROS."""
import math
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Grid:
    """width/height in cells, resolution in m/cell, origin = (x, y, yaw) of cell (0, 0)'s lower-left
    corner in the map frame [m, m, rad]; data: int8 array (height, width), row 0 = lowest y;
    values -1 unknown, 0..100 occupancy probability in percent."""
    width: int
    height: int
    resolution: float
    origin: tuple = (0.0, 0.0, 0.0)
    data: np.ndarray = field(default=None, repr=False)

    def __post_init__(self):
        if self.data is None:
            self.data = np.full((self.height, self.width), -1, dtype=np.int8)
        self.data = np.asarray(self.data, dtype=np.int8).reshape(self.height, self.width)

    def world_to_cell(self, x, y):
        """(x, y) [m] in the map frame -> (col, row) indices (may be out of range)."""
        ox, oy, yaw = self.origin
        dx, dy = x - ox, y - oy
        c, s = math.cos(-yaw), math.sin(-yaw)
        lx, ly = c * dx - s * dy, s * dx + c * dy
        return int(math.floor(lx / self.resolution)), int(math.floor(ly / self.resolution))
