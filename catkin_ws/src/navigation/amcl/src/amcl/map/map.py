"""The filter's occupancy map (amcl's map_t): cell states -1 free, 0 unknown, +1 occupied and
the distance from every cell to the nearest occupied cell, capped at max_occ_dist (amcl's
map_update_cspace). Coordinates: cell (i, j) = (column, row) covers
[origin_x + i*res, origin_x + (i+1)*res) x [origin_y + j*res, ...)."""
import numpy as np
from scipy import ndimage

OCC_FREE = -1
OCC_UNKNOWN = 0
OCC_OCCUPIED = 1


class Map:
    def __init__(self, cells, resolution, origin_x=0.0, origin_y=0.0):
        """cells: (height, width) array of -1/0/+1; resolution in m/cell; origin: world
        coordinates of the lower-left corner of cell (0, 0)."""
        cells = np.asarray(cells, dtype=np.int8)
        if cells.ndim != 2 or cells.size == 0:
            raise ValueError('map cells must be a non-empty 2-D array, got shape %s' % (cells.shape,))
        if not resolution > 0:
            raise ValueError('map resolution must be > 0, got %r' % (resolution,))
        self.cells = cells
        self.height, self.width = cells.shape
        self.resolution = float(resolution)
        self.origin_x = float(origin_x)
        self.origin_y = float(origin_y)
        self.max_occ_dist = 0.0
        self.occ_dist = None
        free_j, free_i = np.nonzero(cells == OCC_FREE)
        self.free_cells = np.stack([free_i, free_j], axis=1)

    def world_to_map(self, x, y):
        """Cell indices (i, j) of world points (arrays)."""
        i = np.floor((np.asarray(x) - self.origin_x) / self.resolution).astype(np.int64)
        j = np.floor((np.asarray(y) - self.origin_y) / self.resolution).astype(np.int64)
        return i, j

    def map_to_world(self, i, j):
        """World coordinates of cell centres."""
        return (self.origin_x + (np.asarray(i) + 0.5) * self.resolution,
                self.origin_y + (np.asarray(j) + 0.5) * self.resolution)

    def valid(self, i, j):
        return (i >= 0) & (i < self.width) & (j >= 0) & (j < self.height)

    def update_cspace(self, max_occ_dist):
        """Distance (m) from each cell centre to the nearest occupied cell centre, capped at
        max_occ_dist (the likelihood field)."""
        self.max_occ_dist = float(max_occ_dist)
        occupied = self.cells == OCC_OCCUPIED
        if not occupied.any():
            self.occ_dist = np.full(self.cells.shape, self.max_occ_dist)
        else:
            d = ndimage.distance_transform_edt(~occupied) * self.resolution
            self.occ_dist = np.minimum(d, self.max_occ_dist)
        return self.occ_dist

    def occ_dist_at(self, x, y):
        """Likelihood-field distance at world points; max_occ_dist outside the map."""
        i, j = self.world_to_map(x, y)
        ok = self.valid(i, j)
        out = np.full(np.shape(i), self.max_occ_dist)
        out[ok] = self.occ_dist[j[ok], i[ok]]
        return out, ok

    def calc_range(self, x, y, theta, max_range):
        """Ray-cast ranges from (x, y) along theta (broadcast arrays), as amcl's
        map_calc_range: distance to the first cell that is not free (or off the map), capped at
        max_range. Half-cell steps, vectorised over all rays."""
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        theta = np.asarray(theta, dtype=float)
        x, y, theta = np.broadcast_arrays(x, y, theta)
        shape = x.shape
        x, y, theta = x.ravel(), y.ravel(), theta.ravel()
        c, s = np.cos(theta), np.sin(theta)
        rng = np.full(x.shape, float(max_range))
        alive = np.ones(x.shape, dtype=bool)
        step = self.resolution * 0.5
        nsteps = int(np.ceil(max_range / step)) + 1
        idx = np.arange(x.size)
        for k in range(nsteps):
            if not idx.size:
                break
            r = k * step
            i, j = self.world_to_map(x[idx] + r * c[idx], y[idx] + r * s[idx])
            ok = self.valid(i, j)
            blocked = ~ok
            blocked[ok] = self.cells[j[ok], i[ok]] != OCC_FREE
            hit = idx[blocked]
            rng[hit] = min(r, max_range)
            alive[hit] = False
            idx = idx[~blocked]
        return rng.reshape(shape)
