"""A synthetic lidar for gmapping's unit tests: ranges of beams at `angles` from a pose against
wall segments (x0, y0, x1, y1); beyond max_range (or no hit) is inf."""
import numpy as np


def raycast(segments, angles, pose, max_range=8.0):
    a = pose[2] + angles
    dx, dy = np.cos(a)[:, None], np.sin(a)[:, None]
    x0, y0, x1, y1 = (segments[:, k][None, :] for k in range(4))
    ex, ey = x1 - x0, y1 - y0
    den = dx * ey - dy * ex
    with np.errstate(divide='ignore', invalid='ignore'):
        t = ((x0 - pose[0]) * ey - (y0 - pose[1]) * ex) / den
        u = ((x0 - pose[0]) * dy - (y0 - pose[1]) * dx) / den
    t[(den == 0) | (t <= 0) | (u < 0) | (u > 1)] = np.inf
    r = t.min(axis=1)
    r[r > max_range] = np.inf
    return r
