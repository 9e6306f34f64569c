"""Synthetic maps and scans for the unit tests (no ROS)."""
import numpy as np

from amcl.map import Map
from amcl.sensors import LaserData


def room_map(res=0.05):
    """A 6 m x 4 m room (walls one cell thick) with an L-shaped block and a pillar, so the
    pose is unambiguous."""
    w, h = int(6.0 / res), int(4.0 / res)
    cells = np.full((h, w), -1, dtype=np.int8)
    cells[0, :] = cells[-1, :] = 1
    cells[:, 0] = cells[:, -1] = 1

    def block(x0, y0, x1, y1):
        cells[int(y0 / res):int(y1 / res), int(x0 / res):int(x1 / res)] = 1
    block(4.0, 2.5, 5.0, 3.0)
    block(4.5, 1.5, 5.0, 3.0)
    block(1.0, 1.0, 1.3, 1.3)
    return Map(cells, res, 0.0, 0.0)


def scan(gmap, pose, beams=360, range_max=12.0, noise=0.0, rng=None, laser_pose=(0.0, 0.0, 0.0)):
    """A simulated scan from robot pose (x, y, yaw) by ray casting on the map."""
    angles = np.linspace(-np.pi, np.pi, beams, endpoint=False)
    lx, ly, lth = laser_pose
    c, s = np.cos(pose[2]), np.sin(pose[2])
    ox, oy = pose[0] + c * lx - s * ly, pose[1] + s * lx + c * ly
    ranges = gmap.calc_range(ox, oy, pose[2] + lth + angles, range_max)
    if noise:
        ranges = ranges + (rng or np.random.default_rng(0)).normal(0, noise, beams)
    return LaserData(np.asarray(ranges), angles, range_max, laser_pose)
