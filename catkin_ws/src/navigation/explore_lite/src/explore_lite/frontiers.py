"""Frontier search on a 2-D costmap (no ROS): the core of explore_lite.

A frontier cell is an unknown cell with a free 4-neighbour that the robot can reach through
cells no costlier than the ones it came from; frontier cells touching each other (8-connected)
form one frontier. As explore_lite, a frontier's cost is
    potential_scale * min_distance - gain_scale * size      (both in metres)
and the cheapest frontier that is not blacklisted becomes the next goal.
Costs follow costmap_2d: FREE_SPACE 0 ... LETHAL_OBSTACLE 254, NO_INFORMATION 255.
"""
from collections import deque
from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage

FREE_SPACE = 0
INSCRIBED_INFLATED_OBSTACLE = 253
LETHAL_OBSTACLE = 254
NO_INFORMATION = 255

_FOUR = ndimage.generate_binary_structure(2, 1)
_EIGHT = ndimage.generate_binary_structure(2, 2)


def occupancy_to_costmap(data):
    """OccupancyGrid values (-1 unknown, 0..100) as costmap_2d costs (the translation table
    explore_lite's Costmap2DClient uses: -1 -> 255, 0 -> 0, 1..98 -> 1..252, 99 -> 253,
    100 -> 254)."""
    data = np.asarray(data, dtype=np.int16)
    cost = np.empty(data.shape, dtype=np.uint8)
    unknown = data < 0
    scaled = np.clip(np.round(1 + (data - 1) * 251.0 / 97.0), 1, 252)
    cost[...] = scaled.astype(np.uint8)
    cost[data == 0] = FREE_SPACE
    cost[data == 99] = INSCRIBED_INFLATED_OBSTACLE
    cost[data >= 100] = LETHAL_OBSTACLE
    cost[unknown] = NO_INFORMATION
    return cost


@dataclass
class Frontier:
    size: int                       # cells
    min_distance: float             # metres from the robot to its nearest cell
    cost: float = 0.0
    initial: tuple = (0.0, 0.0)     # world position of the first cell found
    centroid: tuple = (0.0, 0.0)
    middle: tuple = (0.0, 0.0)      # the frontier cell nearest the robot
    points: list = field(default_factory=list)   # world positions of its cells


class Grid:
    """A costmap with its geometry: costs[row=y, col=x], resolution, origin (x, y) of cell (0, 0)."""

    def __init__(self, costs, resolution, origin):
        self.costs = np.asarray(costs, dtype=np.uint8)
        self.resolution = float(resolution)
        self.origin = (float(origin[0]), float(origin[1]))

    def world_to_cell(self, x, y):
        cx = int(np.floor((x - self.origin[0]) / self.resolution))
        cy = int(np.floor((y - self.origin[1]) / self.resolution))
        h, w = self.costs.shape
        if 0 <= cx < w and 0 <= cy < h:
            return cy, cx
        return None

    def cell_to_world(self, row, col):
        return (self.origin[0] + (col + 0.5) * self.resolution,
                self.origin[1] + (row + 0.5) * self.resolution)


def nearest_free_cell(grid, start):
    """The free cell nearest `start` (row, col) by breadth-first search, or None."""
    costs = grid.costs
    h, w = costs.shape
    seen = np.zeros(costs.shape, dtype=bool)
    todo = deque([start])
    seen[start] = True
    while todo:
        r, c = todo.popleft()
        if costs[r, c] == FREE_SPACE:
            return r, c
        for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            rr, cc = r + dr, c + dc
            if 0 <= rr < h and 0 <= cc < w and not seen[rr, cc]:
                seen[rr, cc] = True
                todo.append((rr, cc))
    return None


def reachable(grid, start):
    """Cells the robot can reach from `start` through known cells cheaper than an inscribed
    obstacle (4-connected): the region explore_lite's search walks."""
    passable = grid.costs < INSCRIBED_INFLATED_OBSTACLE
    labels, _ = ndimage.label(passable, structure=_FOUR)
    if not passable[start]:
        return np.zeros(passable.shape, dtype=bool)
    return labels == labels[start]


def search(grid, robot_xy, potential_scale=1e-3, gain_scale=1.0, min_frontier_size=0.5):
    """Frontiers reachable from the robot, cheapest first (a list of Frontier)."""
    cell = grid.world_to_cell(*robot_xy)
    if cell is None:
        raise ValueError('robot position (%.2f, %.2f) is outside the costmap' % robot_xy)
    start = nearest_free_cell(grid, cell)
    if start is None:
        return []
    region = reachable(grid, start)
    unknown = grid.costs == NO_INFORMATION
    # unknown cells with a reachable free 4-neighbour
    free_reach = region & (grid.costs == FREE_SPACE)
    candidates = unknown & ndimage.binary_dilation(free_reach, structure=_FOUR)
    labels, n = ndimage.label(candidates, structure=_EIGHT)
    if n == 0:
        return []
    res = grid.resolution
    rx, ry = robot_xy
    found = []
    for index, cells in enumerate(ndimage.find_objects(labels), start=1):
        rows, cols = np.nonzero(labels[cells] == index)
        rows = rows + cells[0].start
        cols = cols + cells[1].start
        xs = grid.origin[0] + (cols + 0.5) * res
        ys = grid.origin[1] + (rows + 0.5) * res
        d = np.hypot(xs - rx, ys - ry)
        near = int(np.argmin(d))
        f = Frontier(size=len(rows), min_distance=float(d[near]),
                     initial=(float(xs[0]), float(ys[0])),
                     centroid=(float(xs.mean()), float(ys.mean())),
                     middle=(float(xs[near]), float(ys[near])),
                     points=list(zip(xs.tolist(), ys.tolist())))
        if f.size * res < min_frontier_size:
            continue
        f.cost = potential_scale * f.min_distance - gain_scale * f.size * res
        found.append(f)
    found.sort(key=lambda f: f.cost)
    return found


class Blacklist:
    """Goals that failed: a frontier whose goal lies within `tolerance` of one is skipped
    (explore_lite uses five cells)."""

    def __init__(self, tolerance):
        self.tolerance = tolerance
        self.goals = []

    def add(self, xy):
        self.goals.append(tuple(xy))

    def __contains__(self, xy):
        return any(abs(g[0] - xy[0]) < self.tolerance and abs(g[1] - xy[1]) < self.tolerance
                   for g in self.goals)


class Progress:
    """explore_lite's progress rule: a goal that stays the same while the robot comes no nearer
    to its frontier for progress_timeout seconds is given up."""

    def __init__(self, timeout):
        self.timeout = timeout
        self.goal = None
        self.distance = None
        self.since = None

    def update(self, goal, distance, now):
        """Returns True when the current goal timed out."""
        same = self.goal is not None and np.hypot(goal[0] - self.goal[0],
                                                  goal[1] - self.goal[1]) < 1e-9
        if not same or self.distance is None or distance < self.distance:
            self.goal, self.distance, self.since = tuple(goal), distance, now
            return False
        return now - self.since > self.timeout
