"""The navigation function (navfn's NavFn): no ROS imports.

Costs: COST_NEUTRAL + COST_FACTOR * costmap cost per cell; INSCRIBED, LETHAL and (unless
allow_unknown) NO_INFORMATION cells are obstacles. The potential spreads from the goal with
navfn's quadratic (two-neighbour) update in Dijkstra order (A* with a distance heuristic
on request); the path descends the potential's interpolated gradient from the start, with
navfn's fallback to the lowest neighbour where the gradient is undefined.
"""
import heapq
import math

import numpy as np

COST_UNKNOWN_ROS = 255
COST_OBS_ROS = 253
COST_OBS = 254
COST_NEUTRAL = 50
COST_FACTOR = 0.8
POT_HIGH = 1.0e10


def navfn_costs(costmap_data, allow_unknown=True):
    """Costmap (uint8 [ny, nx]) -> navfn cost array (float [ny, nx]); borders are obstacles."""
    c = np.asarray(costmap_data).astype(np.float64)
    out = np.full(c.shape, float(COST_OBS))
    free = c < COST_OBS_ROS
    v = COST_NEUTRAL + COST_FACTOR * c[free]
    out[free] = np.minimum(v, COST_OBS - 1)
    if allow_unknown:
        out[c == COST_UNKNOWN_ROS] = COST_OBS - 1
    out[0, :] = out[-1, :] = COST_OBS
    out[:, 0] = out[:, -1] = COST_OBS
    return out


def propagate(costs, goal, start=None, astar=False, extra=None, native=True):
    """Potential array (POT_HIGH where unreached) spreading from goal=(x, y) cell.
    Stops once start=(x, y) is settled, then settles `extra` more cells (default: enough for
    a clean gradient around the start). Returns the potential [ny, nx]."""
    ny, nx = costs.shape
    if native:
        from . import native as _native
        return _native.propagate(costs, goal, start,
                                 extra if extra is not None else 4 * (nx + ny),
                                 COST_NEUTRAL if astar else 0.0,
                                 start if start is not None else (0, 0))
    cost = costs.ravel().tolist()
    pot = [POT_HIGH] * (nx * ny)
    done = bytearray(nx * ny)
    g = goal[1] * nx + goal[0]
    if cost[g] >= COST_OBS:
        return np.full(costs.shape, POT_HIGH)
    s = None if start is None else start[1] * nx + start[0]
    sx, sy = (start if start is not None else (0, 0))
    pot[g] = 0.0
    heap = [(0.0, g)]
    remaining = None
    h_scale = COST_NEUTRAL if astar else 0.0
    while heap:
        _, n = heapq.heappop(heap)
        if done[n]:
            continue
        done[n] = 1
        if remaining is not None:
            remaining -= 1
            if remaining <= 0:
                break
        elif n == s:
            remaining = (extra if extra is not None else 4 * (nx + ny))
        nyy, nxx = divmod(n, nx)
        for m in (n - 1, n + 1, n - nx, n + nx):
            if m < 0 or m >= nx * ny or done[m]:
                continue
            my, mx = divmod(m, nx)
            if abs(mx - nxx) + abs(my - nyy) != 1:
                continue
            hf = cost[m]
            if hf >= COST_OBS:
                continue
            # navfn's updateCell: the two smallest neighbour potentials, one per axis
            l = pot[m - 1] if mx > 0 else POT_HIGH
            r = pot[m + 1] if mx < nx - 1 else POT_HIGH
            u = pot[m - nx] if my > 0 else POT_HIGH
            d = pot[m + nx] if my < ny - 1 else POT_HIGH
            ta = l if l < r else r
            tc = u if u < d else d
            if ta > tc:
                ta, tc = tc, ta
            dc = tc - ta
            if dc >= hf:
                p = ta + hf
            else:
                dd = dc / hf
                p = ta + hf * (-0.2301 * dd * dd + 0.5307 * dd + 0.7040)
            if p < pot[m]:
                pot[m] = p
                key = p
                if h_scale:
                    key += h_scale * math.hypot(mx - sx, my - sy)
                heapq.heappush(heap, (key, m))
    return np.array(pot).reshape(ny, nx)


def _slope(before, p, after):
    """Downhill slope along one axis at a cell of potential P between the neighbours BEFORE and
    AFTER: the central difference where both are defined, else one-sided; a missing neighbour
    (POT_HIGH) is an obstacle, 0 with neither."""
    if before < POT_HIGH and after < POT_HIGH:
        return (before - after) / 2.0
    if before < POT_HIGH:
        return before - p
    if after < POT_HIGH:
        return p - after
    return 0.0


def _gradient(pot, x, y):
    """navfn's gradCell at an integer cell: normalised (gx, gy) pointing downhill."""
    ny, nx = pot.shape
    p = pot[y, x]
    if p >= POT_HIGH:
        return None

    def val(xx, yy):
        if 0 <= xx < nx and 0 <= yy < ny:
            return pot[yy, xx]
        return POT_HIGH
    gx = _slope(val(x - 1, y), p, val(x + 1, y))
    gy = _slope(val(x, y - 1), p, val(x, y + 1))
    n = math.hypot(gx, gy)
    if n == 0:
        return None
    return gx / n, gy / n


def extract_path(pot, start, goal, step=0.5, max_cycles=None):
    """Cell-coordinate path (list of (x, y) floats) from start down to the goal, or []."""
    ny, nx = pot.shape
    x, y = float(start[0]), float(start[1])
    if pot[int(y), int(x)] >= POT_HIGH:
        return []
    path = [(x, y)]
    max_cycles = max_cycles or 4 * (nx + ny) * 4
    gx_goal, gy_goal = goal
    for _ in range(max_cycles):
        cx, cy = int(round(x)), int(round(y))
        if abs(x - gx_goal) <= 1.0 and abs(y - gy_goal) <= 1.0:
            path.append((float(gx_goal), float(gy_goal)))
            return path
        ix, iy = int(math.floor(x)), int(math.floor(y))
        dx, dy = x - ix, y - iy
        grads = []
        ok = True
        for (ox, oy, w) in ((0, 0, (1 - dx) * (1 - dy)), (1, 0, dx * (1 - dy)),
                            (0, 1, (1 - dx) * dy), (1, 1, dx * dy)):
            xx, yy = ix + ox, iy + oy
            if not (0 <= xx < nx and 0 <= yy < ny):
                ok = False
                break
            gr = _gradient(pot, xx, yy)
            near_obstacle = any(
                not (0 <= xx + a < nx and 0 <= yy + b < ny) or pot[yy + b, xx + a] >= POT_HIGH
                for a, b in ((-1, 0), (1, 0), (0, -1), (0, 1)))
            if gr is None or near_obstacle:
                ok = False
                break
            grads.append((gr[0] * w, gr[1] * w))
        oscillating = len(path) > 3 and math.hypot(path[-1][0] - path[-3][0],
                                                   path[-1][1] - path[-3][1]) < 0.01
        if ok and not oscillating:
            gx = sum(g[0] for g in grads)
            gy = sum(g[1] for g in grads)
            n = math.hypot(gx, gy)
            if n == 0:
                ok = False
            else:
                x += step * gx / n
                y += step * gy / n
        if not ok or oscillating:
            # the lowest of the 8 neighbours of the nearest cell
            best = None
            for a in (-1, 0, 1):
                for b in (-1, 0, 1):
                    if a == 0 and b == 0:
                        continue
                    xx, yy = cx + a, cy + b
                    if 0 <= xx < nx and 0 <= yy < ny and pot[yy, xx] < POT_HIGH:
                        if best is None or pot[yy, xx] < best[0]:
                            best = (pot[yy, xx], xx, yy)
            if best is None:
                return []
            x, y = float(best[1]), float(best[2])
        path.append((x, y))
    return []


class NavFn:
    """Plan on a costmap grid in cell coordinates."""

    def __init__(self, allow_unknown=True, astar=False):
        self.allow_unknown = allow_unknown
        self.astar = astar
        self.potential = None

    def plan(self, costmap_data, start, goal, tolerance_cells=0.0):
        """start, goal: integer cells (x, y). As NavfnROS, the potential spreads from the
        robot (start); the path runs from the goal (or, within tolerance_cells of it, the
        reachable cell nearest to it) down to the start and is returned start first, in cell
        coordinates. [] when there is no path."""
        costs = navfn_costs(costmap_data, self.allow_unknown)
        ny, nx = costs.shape
        sx, sy = start
        gx, gy = goal
        if not (0 <= sx < nx and 0 <= sy < ny and 0 <= gx < nx and 0 <= gy < ny):
            return []
        # the robot's own cell is always free (clearRobotCell)
        costs[sy, sx] = min(costs[sy, sx], COST_NEUTRAL)
        stop_at = None if tolerance_cells > 0 else (gx, gy)
        self.potential = propagate(costs, (sx, sy), stop_at, self.astar and stop_at is not None)
        pot = self.potential
        best = None
        if pot[gy, gx] < POT_HIGH:
            best = (gx, gy)
        elif tolerance_cells > 0:
            r = int(math.ceil(tolerance_cells))
            best_d = None
            for yy in range(max(gy - r, 0), min(gy + r, ny - 1) + 1):
                for xx in range(max(gx - r, 0), min(gx + r, nx - 1) + 1):
                    d = math.hypot(xx - gx, yy - gy)
                    if d <= tolerance_cells and pot[yy, xx] < POT_HIGH and \
                            (best_d is None or d < best_d):
                        best, best_d = (xx, yy), d
        if best is None:
            return []
        path = extract_path(pot, best, (sx, sy))
        path.reverse()
        return path
