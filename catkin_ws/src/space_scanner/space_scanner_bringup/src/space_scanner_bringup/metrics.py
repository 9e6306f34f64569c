"""Figures of the main demo against ground truth (no ROS): trajectory error and map quality.

Maps are (cells, resolution, origin) with cells[row=y, col=x] in map_server's trinary values:
100 occupied, 0 free, -1 unknown.
"""

import numpy as np
from scipy import ndimage


def ate(estimate, truth):
    """Absolute trajectory error (RMS, max) in metres between two lists of (t, x, y): each
    estimate is compared with the ground truth interpolated at its time."""
    if not estimate or len(truth) < 2:
        raise ValueError('ATE needs an estimate and at least two ground-truth poses')
    tt = np.array([p[0] for p in truth])
    tx = np.array([p[1] for p in truth])
    ty = np.array([p[2] for p in truth])
    e = np.array([p for p in estimate if tt[0] <= p[0] <= tt[-1]])
    if len(e) == 0:
        raise ValueError('no estimate inside the ground truth time span')
    gx = np.interp(e[:, 0], tt, tx)
    gy = np.interp(e[:, 0], tt, ty)
    err = np.hypot(e[:, 1] - gx, e[:, 2] - gy)
    return float(np.sqrt(np.mean(err ** 2))), float(err.max())


def cell_centres(cells, resolution, origin, value):
    rows, cols = np.nonzero(cells == value)
    return np.stack([origin[0] + (cols + 0.5) * resolution,
                     origin[1] + (rows + 0.5) * resolution], axis=1)


def lookup(cells, resolution, origin, points, outside=-1):
    """Values of `cells` at world points (outside the grid: `outside`)."""
    h, w = cells.shape
    c = np.floor((points[:, 0] - origin[0]) / resolution).astype(int)
    r = np.floor((points[:, 1] - origin[1]) / resolution).astype(int)
    inside = (c >= 0) & (c < w) & (r >= 0) & (r < h)
    out = np.full(len(points), outside, dtype=cells.dtype)
    out[inside] = cells[r[inside], c[inside]]
    return out


def map_quality(slam, truth, tolerance_cells=1):
    """Compare a built map with the ground-truth map. Returns a dict:
    walls_found  — of the ground truth's wall cells the robot could see (next to free floor the
                   built map also knows), the fraction with an occupied built cell within
                   `tolerance_cells`;
    false_occupied — of the built map's occupied cells, the fraction with no ground-truth wall
                   within `tolerance_cells`;
    known_area   — m² of floor the built map knows (free)."""
    s_cells, s_res, s_org = slam
    g_cells, g_res, g_org = truth
    grow = ndimage.generate_binary_structure(2, 2)
    # built occupied cells, grown by the tolerance, looked up at the ground truth's wall cells
    s_occ = ndimage.binary_dilation(s_cells == 100, grow, iterations=tolerance_cells)
    s_known = ndimage.binary_dilation(s_cells == 0, grow, iterations=tolerance_cells + 1)
    g_walls = cell_centres(g_cells, g_res, g_org, 100)
    g_free_near = ndimage.binary_dilation(g_cells == 0, grow)
    near_floor = lookup(g_free_near.astype(np.int8), g_res, g_org, g_walls) == 1
    seen = near_floor & (lookup(s_known.astype(np.int8), s_res, s_org, g_walls) == 1)
    found = lookup(s_occ.astype(np.int8), s_res, s_org, g_walls[seen]) == 1
    g_occ = ndimage.binary_dilation(g_cells == 100, grow, iterations=tolerance_cells)
    s_walls = cell_centres(s_cells, s_res, s_org, 100)
    false = lookup(g_occ.astype(np.int8), g_res, g_org, s_walls, outside=0) == 0
    return {
        'walls_found': float(found.mean()) if len(found) else 0.0,
        'walls_seen': int(seen.sum()),
        'false_occupied': float(false.mean()) if len(false) else 0.0,
        'known_area': float((s_cells == 0).sum() * s_res * s_res),
    }


def path_length(points):
    pts = np.asarray([(p[-2], p[-1]) for p in points], dtype=float)
    if len(pts) < 2:
        return 0.0
    return float(np.hypot(*np.diff(pts, axis=0).T).sum())
