"""The layered costmap and its three layers (static, obstacle, inflation): no ROS imports.

Each cycle LayeredCostmap.update_map() moves a rolling window, lets every enabled layer
update its own state (update_bounds) and then writes the master grid, layer by layer in
order (update_costs), as layered_costmap.cpp does.
"""
import math

import numpy as np
from scipy import ndimage

from .costmap import (Costmap2D, FREE_SPACE, INSCRIBED_INFLATED_OBSTACLE, LETHAL_OBSTACLE,
                      NO_INFORMATION, calculate_min_and_max_distances, transform_footprint)


class Layer:
    """costmap_2d::Layer: subclasses override the hooks they need."""

    def __init__(self, name):
        self.name = name
        self.enabled = True
        self.current = True
        self.layered = None

    def initialize(self, layered):
        self.layered = layered

    def match_size(self):
        pass

    def update_origin(self, ox, oy):
        pass

    def update_bounds(self, robot_x, robot_y, robot_yaw):
        pass

    def update_costs(self, master):
        pass

    def on_footprint_changed(self):
        pass

    def reset(self):
        pass


class StaticLayer(Layer):
    """An OccupancyGrid map (values -1, 0..100) turned into costs."""

    def __init__(self, name='static_layer', track_unknown_space=True, use_maximum=False,
                 lethal_cost_threshold=100, unknown_cost_value=-1, trinary_costmap=True):
        super().__init__(name)
        self.track_unknown_space = track_unknown_space
        self.use_maximum = use_maximum
        self.lethal_threshold = max(min(int(lethal_cost_threshold), 100), 0)
        self.unknown_cost_value = int(unknown_cost_value)
        self.trinary_costmap = trinary_costmap
        self.map = None          # Costmap2D in the map's own frame and size
        self.current = False
        # pose of the map's frame in the costmap's global frame (x, y, yaw); identity when the
        # map is in the global frame (the ROS side sets it for a rolling window in odom)
        self.map_transform = (0.0, 0.0, 0.0)

    def interpret(self, values):
        values = np.asarray(values, dtype=np.int16)
        out = np.empty(values.shape, dtype=np.uint8)
        unknown = values == self.unknown_cost_value
        lethal = (values >= self.lethal_threshold) & ~unknown
        rest = ~unknown & ~lethal
        if self.trinary_costmap:
            out[rest] = FREE_SPACE
        else:
            out[rest] = (values[rest].astype(float) / self.lethal_threshold
                         * LETHAL_OBSTACLE).astype(np.uint8)
        out[lethal] = LETHAL_OBSTACLE
        out[unknown] = NO_INFORMATION if self.track_unknown_space else FREE_SPACE
        return out

    def set_map(self, width, height, resolution, origin_x, origin_y, values):
        """values: row-major OccupancyGrid data (height*width)."""
        grid = Costmap2D(width, height, resolution, origin_x, origin_y, NO_INFORMATION)
        grid.data = self.interpret(np.asarray(values).reshape(height, width))
        self.map = grid
        self.current = True
        if self.layered is not None and not self.layered.rolling_window:
            master = self.layered.costmap
            if (master.size_x != width or master.size_y != height or
                    master.resolution != resolution or master.origin_x != origin_x or
                    master.origin_y != origin_y):
                self.layered.resize_map(width, height, resolution, origin_x, origin_y)

    def update_costs(self, master):
        if self.map is None or not self.enabled:
            return
        if not self.layered.rolling_window and master.data.shape == self.map.data.shape and \
                self.map_transform == (0.0, 0.0, 0.0):
            src = self.map.data
            if self.use_maximum:
                self._max_into(master.data, src)
            else:
                master.data[:, :] = src
            return
        # rolling window (or a master of another size): look every master cell up in the map
        gx, gy = np.meshgrid(np.arange(master.size_x), np.arange(master.size_y))
        wx = master.origin_x + (gx + 0.5) * master.resolution
        wy = master.origin_y + (gy + 0.5) * master.resolution
        tx, ty, tyaw = self.map_transform
        if (tx, ty, tyaw) != (0.0, 0.0, 0.0):
            c, s = math.cos(tyaw), math.sin(tyaw)
            dx, dy = wx - tx, wy - ty
            wx, wy = c * dx + s * dy, -s * dx + c * dy
        mx, my, inside = self.map.world_to_map_array(wx, wy)
        vals = np.full(master.data.shape, NO_INFORMATION, dtype=np.uint8)
        vals[inside] = self.map.data[my[inside], mx[inside]]
        if self.use_maximum:
            self._max_into(master.data, vals)
        else:
            master.data[inside] = vals[inside]

    @staticmethod
    def _max_into(dst, src):
        take = (src != NO_INFORMATION) & ((dst == NO_INFORMATION) | (dst < src))
        dst[take] = src[take]


class Observation:
    """Points in the global frame seen from origin (x, y, z), with the source's ranges."""

    def __init__(self, origin, points, obstacle_range=2.5, raytrace_range=3.0):
        self.origin = tuple(float(v) for v in origin)
        self.points = np.asarray(points, dtype=float).reshape(-1, 3)
        self.obstacle_range = float(obstacle_range)
        self.raytrace_range = float(raytrace_range)


class ObstacleLayer(Layer):
    """Marks observed points LETHAL and clears the cells along each ray (raytracing)."""

    def __init__(self, name='obstacle_layer', track_unknown_space=False, combination_method=1,
                 footprint_clearing_enabled=True, max_obstacle_height=2.0):
        super().__init__(name)
        self.track_unknown_space = track_unknown_space
        self.combination_method = int(combination_method)
        self.footprint_clearing_enabled = footprint_clearing_enabled
        self.max_obstacle_height = float(max_obstacle_height)
        self.grid = Costmap2D()
        self.marking = []     # list of Observation, replaced every cycle by the ROS side
        self.clearing = []

    def match_size(self):
        m = self.layered.costmap
        self.grid = Costmap2D(m.size_x, m.size_y, m.resolution, m.origin_x, m.origin_y,
                              NO_INFORMATION if self.track_unknown_space else FREE_SPACE)

    def update_origin(self, ox, oy):
        self.grid.update_origin(ox, oy)

    def reset(self):
        self.grid.reset_map()

    def set_observations(self, marking, clearing):
        self.marking = list(marking)
        self.clearing = list(clearing)

    def raytrace_freespace(self, obs):
        """Clear the cells from the sensor origin towards each point, up to raytrace_range
        and the map's edge (the original's raytraceFreespace)."""
        g = self.grid
        ox, oy = obs.origin[0], obs.origin[1]
        if g.world_to_map(ox, oy) is None:
            return
        pts = obs.points
        if len(pts) == 0:
            return
        dx = pts[:, 0] - ox
        dy = pts[:, 1] - oy
        length = np.hypot(dx, dy)
        # clip to the map's edge: scale the ray so that its end stays inside the grid
        map_end_x = g.origin_x + g.size_x * g.resolution
        map_end_y = g.origin_y + g.size_y * g.resolution
        scale = np.ones_like(length)
        with np.errstate(divide='ignore', invalid='ignore'):
            for lim, d, o in ((g.origin_x, dx, ox), (map_end_x - 1e-3 * g.resolution, dx, ox),
                              (g.origin_y, dy, oy), (map_end_y - 1e-3 * g.resolution, dy, oy)):
                t = (lim - o) / d
                bad = (t > 0) & (t < scale)
                scale = np.where(bad, t, scale)
        length = np.minimum(length * scale, obs.raytrace_range)
        ux = np.where(length > 0, dx / np.maximum(np.hypot(dx, dy), 1e-12), 0.0)
        uy = np.where(length > 0, dy / np.maximum(np.hypot(dx, dy), 1e-12), 0.0)
        step = g.resolution * 0.5
        n = int(np.ceil(length.max() / step)) + 1 if len(length) else 0
        s = np.arange(n) * step                       # (n,)
        sx = ox + ux[:, None] * s[None, :]
        sy = oy + uy[:, None] * s[None, :]
        valid = s[None, :] <= length[:, None]
        mx, my, inside = g.world_to_map_array(sx, sy)
        keep = valid & inside
        g.data[my[keep], mx[keep]] = FREE_SPACE
        # the end cell of each ray too (bresenham2D's last at(offset))
        ex, ey, ein = g.world_to_map_array(ox + ux * length, oy + uy * length)
        g.data[ey[ein], ex[ein]] = FREE_SPACE

    def mark(self, obs):
        g = self.grid
        pts = obs.points
        if len(pts) == 0:
            return
        ok = pts[:, 2] <= self.max_obstacle_height
        d2 = (pts[:, 0] - obs.origin[0]) ** 2 + (pts[:, 1] - obs.origin[1]) ** 2 + \
            (pts[:, 2] - obs.origin[2]) ** 2
        ok &= d2 < obs.obstacle_range ** 2
        mx, my, inside = g.world_to_map_array(pts[ok, 0], pts[ok, 1])
        g.data[my[inside], mx[inside]] = LETHAL_OBSTACLE

    def update_bounds(self, robot_x, robot_y, robot_yaw):
        if not self.enabled:
            return
        for obs in self.clearing:
            self.raytrace_freespace(obs)
        for obs in self.marking:
            self.mark(obs)
        if self.footprint_clearing_enabled and self.layered.footprint:
            poly = transform_footprint(robot_x, robot_y, robot_yaw, self.layered.footprint)
            self.grid.set_convex_polygon_cost(poly, FREE_SPACE)

    def update_costs(self, master):
        if not self.enabled:
            return
        src = self.grid.data
        if self.combination_method == 0:      # overwrite
            keep = src != NO_INFORMATION
            master.data[keep] = src[keep]
        else:                                 # maximum
            StaticLayer._max_into(master.data, src)


def inflation_cost(distance_cells, resolution, inscribed_radius, cost_scaling_factor):
    """The original's InflationLayer::computeCost for a distance in cells (array or scalar):
    LETHAL at 0, INSCRIBED within the inscribed radius, else
    (INSCRIBED - 1) * exp(-cost_scaling_factor * (d - inscribed_radius))."""
    d = np.asarray(distance_cells, dtype=float)
    dm = d * resolution
    factor = np.exp(-1.0 * cost_scaling_factor * (dm - inscribed_radius))
    cost = ((INSCRIBED_INFLATED_OBSTACLE - 1) * factor).astype(np.int64)
    cost = np.where(dm <= inscribed_radius, INSCRIBED_INFLATED_OBSTACLE, cost)
    cost = np.where(d == 0, LETHAL_OBSTACLE, cost)
    return cost.astype(np.uint8) if cost.ndim else int(cost)


class InflationLayer(Layer):
    def __init__(self, name='inflation_layer', inflation_radius=0.55, cost_scaling_factor=10.0,
                 inflate_unknown=False):
        super().__init__(name)
        self.inflation_radius = float(inflation_radius)
        self.cost_scaling_factor = float(cost_scaling_factor)
        self.inflate_unknown = inflate_unknown
        self.inscribed_radius = 0.0

    def on_footprint_changed(self):
        self.inscribed_radius = self.layered.inscribed_radius

    def update_costs(self, master):
        if not self.enabled:
            return
        data = master.data
        lethal = data == LETHAL_OBSTACLE
        if not lethal.any():
            return
        res = master.resolution
        cell_radius = self.inflation_radius / res
        dist = ndimage.distance_transform_edt(~lethal)
        near = dist <= cell_radius
        cost = inflation_cost(dist[near], res, self.inscribed_radius, self.cost_scaling_factor)
        old = data[near]
        unknown = old == NO_INFORMATION
        if self.inflate_unknown:
            set_unknown = unknown & (cost > FREE_SPACE)
        else:
            set_unknown = unknown & (cost >= INSCRIBED_INFLATED_OBSTACLE)
        new = np.where(unknown, np.where(set_unknown, cost, old), np.maximum(old, cost))
        data[near] = new


class LayeredCostmap:
    def __init__(self, global_frame='map', rolling_window=False, track_unknown=False):
        self.global_frame = global_frame
        self.rolling_window = rolling_window
        self.costmap = Costmap2D(default_value=NO_INFORMATION if track_unknown else FREE_SPACE)
        self.plugins = []
        self.footprint = []
        self.inscribed_radius = 0.0
        self.circumscribed_radius = 0.0
        self.size_locked = False

    def add_plugin(self, layer):
        layer.initialize(self)
        self.plugins.append(layer)
        layer.match_size()
        layer.on_footprint_changed()

    def resize_map(self, size_x, size_y, resolution, origin_x, origin_y, size_locked=False):
        self.size_locked = size_locked
        self.costmap.resize(size_x, size_y, resolution, origin_x, origin_y)
        for p in self.plugins:
            p.match_size()

    def set_footprint(self, footprint):
        self.footprint = list(footprint)
        self.inscribed_radius, self.circumscribed_radius = \
            calculate_min_and_max_distances(self.footprint)
        for p in self.plugins:
            p.on_footprint_changed()

    def is_current(self):
        return all(p.current for p in self.plugins if p.enabled)

    def update_map(self, robot_x, robot_y, robot_yaw):
        m = self.costmap
        if self.rolling_window:
            new_ox = robot_x - m.size_x * m.resolution / 2.0
            new_oy = robot_y - m.size_y * m.resolution / 2.0
            m.update_origin(new_ox, new_oy)
            for p in self.plugins:
                p.update_origin(new_ox, new_oy)
        for p in self.plugins:
            if p.enabled:
                p.update_bounds(robot_x, robot_y, robot_yaw)
        m.reset_map()
        for p in self.plugins:
            if p.enabled:
                p.update_costs(m)
