"""The cost grid (costmap_2d::Costmap2D) and footprint helpers: no ROS imports.

The grid is a NumPy uint8 array indexed [my, mx] (row = y), origin at the lower-left corner
of cell (0, 0), as in the original.
"""
import math

import numpy as np

FREE_SPACE = 0
INSCRIBED_INFLATED_OBSTACLE = 253
LETHAL_OBSTACLE = 254
NO_INFORMATION = 255


class Costmap2D:
    def __init__(self, size_x=0, size_y=0, resolution=0.05, origin_x=0.0, origin_y=0.0,
                 default_value=FREE_SPACE):
        self.default_value = default_value
        self.resize(size_x, size_y, resolution, origin_x, origin_y)

    def resize(self, size_x, size_y, resolution, origin_x, origin_y):
        self.size_x, self.size_y = int(size_x), int(size_y)
        self.resolution = float(resolution)
        self.origin_x, self.origin_y = float(origin_x), float(origin_y)
        self.data = np.full((self.size_y, self.size_x), self.default_value, dtype=np.uint8)

    def reset_map(self, x0=0, y0=0, xn=None, yn=None):
        xn = self.size_x if xn is None else xn
        yn = self.size_y if yn is None else yn
        self.data[y0:yn, x0:xn] = self.default_value

    @property
    def size_in_meters(self):
        return (self.size_x * self.resolution, self.size_y * self.resolution)

    def world_to_map(self, wx, wy):
        """(mx, my) or None when outside the grid."""
        if wx < self.origin_x or wy < self.origin_y:
            return None
        mx = int((wx - self.origin_x) / self.resolution)
        my = int((wy - self.origin_y) / self.resolution)
        if mx < self.size_x and my < self.size_y:
            return mx, my
        return None

    def world_to_map_array(self, wx, wy):
        """Vectorised: integer cell arrays and a mask of the points inside the grid."""
        fx = np.floor((np.asarray(wx) - self.origin_x) / self.resolution).astype(np.int64)
        fy = np.floor((np.asarray(wy) - self.origin_y) / self.resolution).astype(np.int64)
        inside = (fx >= 0) & (fy >= 0) & (fx < self.size_x) & (fy < self.size_y)
        return fx, fy, inside

    def map_to_world(self, mx, my):
        return (self.origin_x + (mx + 0.5) * self.resolution,
                self.origin_y + (my + 0.5) * self.resolution)

    def get_cost(self, mx, my):
        return int(self.data[my, mx])

    def set_cost(self, mx, my, cost):
        self.data[my, mx] = cost

    def update_origin(self, new_origin_x, new_origin_y):
        """Rolling window: move the origin by whole cells, keeping the overlapping data."""
        cell_ox = int((new_origin_x - self.origin_x) / self.resolution)
        cell_oy = int((new_origin_y - self.origin_y) / self.resolution)
        if cell_ox == 0 and cell_oy == 0:
            return
        new = np.full_like(self.data, self.default_value)
        sx, sy = self.size_x, self.size_y
        x0, x1 = max(0, cell_ox), min(sx, sx + cell_ox)
        y0, y1 = max(0, cell_oy), min(sy, sy + cell_oy)
        if x0 < x1 and y0 < y1:
            new[y0 - cell_oy:y1 - cell_oy, x0 - cell_ox:x1 - cell_ox] = self.data[y0:y1, x0:x1]
        self.data = new
        self.origin_x += cell_ox * self.resolution
        self.origin_y += cell_oy * self.resolution

    def polygon_cells(self, polygon):
        """Cells (mx, my arrays) of a convex world-frame polygon as the original's
        convexFillCells: the outline rasterized between the vertices' cells (Bresenham), then
        every column filled between its lowest and highest outline cell. None when a vertex
        is off the map."""
        poly = np.asarray(polygon, dtype=float)
        if len(poly) < 3:
            return np.zeros(0, int), np.zeros(0, int)
        vx, vy, inside = self.world_to_map_array(poly[:, 0], poly[:, 1])
        if not inside.all():
            return np.zeros(0, int), np.zeros(0, int)
        xs, ys = [], []
        n = len(poly)
        for i in range(n):
            lx, ly = bresenham(int(vx[i]), int(vy[i]), int(vx[(i + 1) % n]), int(vy[(i + 1) % n]))
            xs.append(lx)
            ys.append(ly)
        ox, oy = np.concatenate(xs), np.concatenate(ys)
        mx, my = [], []
        for x in np.unique(ox):
            col = oy[ox == x]
            y0, y1 = int(col.min()), int(col.max())
            mx.append(np.full(y1 - y0 + 1, x))
            my.append(np.arange(y0, y1 + 1))
        return np.concatenate(mx), np.concatenate(my)

    def set_convex_polygon_cost(self, polygon, cost):
        mx, my = self.polygon_cells(polygon)
        self.data[my, mx] = cost
        return len(mx) > 0


def bresenham(x0, y0, x1, y1):
    """The cells of the line from (x0, y0) to (x1, y1), both ends included (the original's
    raytraceLine / LineIterator order)."""
    dx, dy = abs(x1 - x0), abs(y1 - y0)
    sx, sy = (1 if x1 >= x0 else -1), (1 if y1 >= y0 else -1)
    n = max(dx, dy)
    xs = np.empty(n + 1, dtype=int)
    ys = np.empty(n + 1, dtype=int)
    x, y = x0, y0
    if dx >= dy:
        num, den, add = dx // 2, dx, dy
    else:
        num, den, add = dy // 2, dy, dx
    for k in range(n + 1):
        xs[k], ys[k] = x, y
        num += add
        if dx >= dy:
            if num >= den:
                num -= den
                y += sy
            x += sx
        else:
            if num >= den:
                num -= den
                x += sx
            y += sy
    return xs, ys


# ---- footprint (costmap_2d/footprint.cpp) ---------------------------------------------

def make_footprint_from_radius(radius):
    """The original's 16-point circle."""
    n = 16
    return [(radius * math.cos(i * 2 * math.pi / n), radius * math.sin(i * 2 * math.pi / n))
            for i in range(n)]


def pad_footprint(footprint, padding):
    return [(x + math.copysign(padding, x) if x != 0 else x,
             y + math.copysign(padding, y) if y != 0 else y) for x, y in footprint]


def _dist_to_segment(px, py, x0, y0, x1, y1):
    dx, dy = x1 - x0, y1 - y0
    l2 = dx * dx + dy * dy
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, ((px - x0) * dx + (py - y0) * dy) / l2))
    return math.hypot(px - (x0 + t * dx), py - (y0 + t * dy))


def calculate_min_and_max_distances(footprint):
    """(inscribed radius, circumscribed radius) of a footprint around the origin."""
    if not footprint:
        return 0.0, 0.0
    min_d = float('inf')
    max_d = 0.0
    n = len(footprint)
    for i in range(n):
        x0, y0 = footprint[i]
        x1, y1 = footprint[(i + 1) % n]
        min_d = min(min_d, _dist_to_segment(0.0, 0.0, x0, y0, x1, y1))
        max_d = max(max_d, math.hypot(x0, y0))
    return min_d, max_d


class FootprintError(ValueError):
    pass


def parse_footprint(value, name='footprint'):
    """A footprint parameter: a list of [x, y] pairs or its string form "[[x, y], ...]"."""
    if isinstance(value, str):
        text = value.strip()
        if not text or text == '[]':
            return []
        import ast
        try:
            value = ast.literal_eval(text)
        except (ValueError, SyntaxError):
            raise FootprintError("Error parsing footprint parameter: '%s'; %s must be a list of "
                                 "[x, y] pairs like [[0.5, 0.5], [0.5, -0.5], [-0.5, -0.5]]"
                                 % (value, name))
    if not isinstance(value, (list, tuple)):
        raise FootprintError("The footprint must be specified as list of lists on the parameter "
                             "server, %s was specified as %r" % (name, value))
    pts = []
    for p in value:
        if not isinstance(p, (list, tuple)) or len(p) != 2:
            raise FootprintError("The footprint must be specified as list of lists on the "
                                 "parameter server, %s was specified as %r" % (name, value))
        try:
            pts.append((float(p[0]), float(p[1])))
        except (TypeError, ValueError):
            raise FootprintError("Values in the footprint specification (param %s) must be "
                                 "numbers. Found value %r." % (name, p))
    if pts and len(pts) < 3:
        raise FootprintError("You must specify at least three points for the robot footprint, "
                             "reverting to previous footprint (param %s)." % name)
    return pts


def transform_footprint(x, y, theta, footprint):
    c, s = math.cos(theta), math.sin(theta)
    return [(x + px * c - py * s, y + px * s + py * c) for px, py in footprint]


# ---- cost values to OccupancyGrid values (costmap_2d_publisher.cpp) ----------------------

def cost_translation_table():
    table = np.zeros(256, dtype=np.int8)
    for i in range(1, 253):
        table[i] = 1 + (97 * (i - 1)) // 251
    table[253] = 99
    table[254] = 100
    table[255] = -1
    return table
