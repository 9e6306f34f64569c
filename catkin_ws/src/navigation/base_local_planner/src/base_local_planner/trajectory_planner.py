"""Trajectory rollout / DWA local planning (base_local_planner's TrajectoryPlanner and
MapGrid): no ROS imports.

Every velocity sample is simulated forward for sim_time, all samples at once in NumPy. A
trajectory is invalid (cost < 0) when the footprint outline touches a lethal or unknown cell
at any step (-1; CostmapModel::footprintCost, compiled: src_cpp/footprint_cost.cpp) or a
point has no obstacle-free route to the path or the goal (-2); otherwise its cost is
    pdist_scale * path_dist(end) + gdist_scale * goal_dist(end) + occdist_scale * occ_cost
with the distances of the last point (in cells, or metres with meter_scoring) taken from
MapGrid wavefronts over the local costmap (the cells under the robot's footprint passable),
and occ_cost the highest cost under the centre or the footprint outline along the way, as
the original.
"""
import math

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph

LETHAL_OBSTACLE = 254
INSCRIBED_INFLATED_OBSTACLE = 253
NO_INFORMATION = 255


class TrajectoryParams:
    """Parameters with the defaults TrajectoryPlannerROS ends up with (the dynamic
    reconfigure defaults, applied at start-up), see ANCHORS §4.2."""

    def __init__(self, **kw):
        self.max_vel_x = 0.55
        self.min_vel_x = 0.0
        self.max_vel_theta = 1.0
        self.min_vel_theta = -1.0
        self.min_in_place_vel_theta = 0.4
        self.acc_lim_x = 2.5
        self.acc_lim_y = 2.5
        self.acc_lim_theta = 3.2
        self.sim_time = 1.7
        self.sim_granularity = 0.025
        self.angular_sim_granularity = 0.025
        self.vx_samples = 20
        self.vtheta_samples = 20
        self.pdist_scale = 0.6
        self.gdist_scale = 0.8
        self.occdist_scale = 0.01
        self.heading_lookahead = 0.325
        self.oscillation_reset_dist = 0.05
        self.escape_reset_dist = 0.10
        self.escape_reset_theta = math.pi / 2
        self.escape_vel = -0.1
        self.holonomic_robot = True
        self.y_vels = [-0.3, -0.1, 0.1, 0.3]
        self.dwa = False
        self.sim_period = 0.1
        self.meter_scoring = False
        self.max_sim_steps = 80
        # the footprint outline's cells: those its edges cross (True), or CostmapModel's
        # Bresenham lines between the vertices' cells (False, the original), which can pass
        # a cell beside the edge and let a wall's corner into the footprint
        self.exact_outline = True
        for k, v in kw.items():
            if not hasattr(self, k):
                raise AttributeError('unknown trajectory parameter %s' % k)
            setattr(self, k, v)


class LocalGrid:
    """A snapshot of the local costmap: data [ny, nx] uint8, resolution, origin."""

    def __init__(self, data, resolution, origin_x, origin_y):
        self.data = np.asarray(data, dtype=np.uint8)
        self.ny, self.nx = self.data.shape
        self.resolution = float(resolution)
        self.origin_x = float(origin_x)
        self.origin_y = float(origin_y)

    def cells(self, wx, wy):
        fx = np.floor((wx - self.origin_x) / self.resolution).astype(np.int64)
        fy = np.floor((wy - self.origin_y) / self.resolution).astype(np.int64)
        inside = (fx >= 0) & (fy >= 0) & (fx < self.nx) & (fy < self.ny)
        return fx, fy, inside


class GridGraph:
    """The 4-connected graph of the non-obstacle cells of a grid (obstacles: lethal,
    inscribed, unknown), for MapGrid wavefronts."""

    def __init__(self, grid, open_cells=None):
        ny, nx = grid.data.shape
        self.shape = (ny, nx)
        self.blocked = grid.data >= INSCRIBED_INFLATED_OBSTACLE
        if open_cells is not None:
            self.blocked &= ~open_cells
        free = ~self.blocked
        idx = np.arange(nx * ny).reshape(ny, nx)
        h = free[:, :-1] & free[:, 1:]
        v = free[:-1, :] & free[1:, :]
        rows = np.concatenate([idx[:, :-1][h], idx[:-1, :][v]])
        cols = np.concatenate([idx[:, 1:][h], idx[1:, :][v]])
        self.graph = sparse.csr_matrix((np.ones(len(rows)), (rows, cols)),
                                       shape=(nx * ny, nx * ny))


def wavefront(grid, seeds, graph=None, native=True, within_robot=None):
    """MapGrid::computeTargetDistance: 4-connected distance (cells) from the seed cells
    (targets whatever their cost) around obstacles (lethal, inscribed, unknown; not the cells
    within_robot, bool [ny, nx]: under the robot's footprint). Unreached cells get the
    impossible value nx * ny + 1 (obstacles: nx * ny)."""
    ny, nx = grid.data.shape
    obstacle_value = nx * ny
    unreachable = nx * ny + 1
    if native:
        from . import native as _native
        blocked = grid.data >= INSCRIBED_INFLATED_OBSTACLE
        if within_robot is not None:
            blocked &= ~within_robot
        return _native.wavefront(blocked, (y * nx + x for x, y in seeds), obstacle_value,
                                 unreachable), obstacle_value
    seed_mask = np.zeros((ny, nx), dtype=bool)
    for x, y in seeds:
        seed_mask[y, x] = True
    if within_robot is not None:
        seed_mask |= within_robot
    graph = graph or GridGraph(grid, seed_mask)
    src = [y * nx + x for x, y in seeds]
    if not src:
        d = np.full((ny, nx), unreachable, dtype=np.int64)
    else:
        dist = csgraph.dijkstra(graph.graph, directed=False, indices=src, min_only=True,
                                unweighted=True)
        d = np.where(np.isfinite(dist), dist, unreachable).astype(np.int64).reshape(ny, nx)
    d[graph.blocked] = obstacle_value
    return d, obstacle_value


def plan_cells(grid, plan_xy):
    """Cells along the plan inside the grid, at most half a cell apart
    (MapGrid::adjustPlanResolution + setTargetCells)."""
    pts = np.asarray(plan_xy, dtype=float).reshape(-1, 2)
    if len(pts) == 0:
        return []
    if len(pts) > 1:
        seg = pts[1:] - pts[:-1]
        n = np.maximum(np.ceil(np.hypot(seg[:, 0], seg[:, 1]) / (grid.resolution * 0.5)),
                       1).astype(int)
        which = np.repeat(np.arange(len(seg)), n)
        frac = (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n) + 1) / np.repeat(n, n)
        dense = np.vstack([pts[:1], pts[which] + seg[which] * frac[:, None]])
    else:
        dense = pts
    fx, fy, inside = grid.cells(dense[:, 0], dense[:, 1])
    fx, fy = fx[inside], fy[inside]
    if len(fx) == 0:
        return []
    keep = np.ones(len(fx), dtype=bool)
    keep[1:] = (fx[1:] != fx[:-1]) | (fy[1:] != fy[:-1])
    return list(zip(fx[keep].tolist(), fy[keep].tolist()))


def footprint_cells(grid, footprint, x, y, th):
    """bool [ny, nx]: the cells under the footprint polygon at pose (x, y, th), outline
    included (FootprintHelper::getFootprintCells with fill)."""
    mask = np.zeros(grid.data.shape, dtype=bool)
    fp = np.asarray(footprint, dtype=float).reshape(-1, 2)
    if len(fp) < 3:
        cx, cy, inside = grid.cells(np.array([x]), np.array([y]))
        if inside[0]:
            mask[cy[0], cx[0]] = True
        return mask
    c, s = math.cos(th), math.sin(th)
    px = x + fp[:, 0] * c - fp[:, 1] * s
    py = y + fp[:, 0] * s + fp[:, 1] * c
    res = grid.resolution
    x0 = max(int(math.floor((px.min() - grid.origin_x) / res)), 0)
    x1 = min(int(math.floor((px.max() - grid.origin_x) / res)), grid.nx - 1)
    y0 = max(int(math.floor((py.min() - grid.origin_y) / res)), 0)
    y1 = min(int(math.floor((py.max() - grid.origin_y) / res)), grid.ny - 1)
    if x0 > x1 or y0 > y1:
        return mask
    gy, gx = np.mgrid[y0:y1 + 1, x0:x1 + 1]
    wx = grid.origin_x + (gx + 0.5) * res
    wy = grid.origin_y + (gy + 0.5) * res
    inside = np.ones(wx.shape, dtype=bool)
    # a convex polygon: inside every edge, on the side its orientation (signed area) says
    sign = 1.0 if np.sum(px * np.roll(py, -1) - np.roll(px, -1) * py) >= 0 else -1.0
    for i in range(len(px)):
        ax, ay, bx, by = px[i], py[i], px[(i + 1) % len(px)], py[(i + 1) % len(px)]
        inside &= ((bx - ax) * (wy - ay) - (by - ay) * (wx - ax)) * sign >= 0
    mask[y0:y1 + 1, x0:x1 + 1] = inside
    ol = footprint_outline(fp, res * 0.5)
    ox = x + ol[:, 0] * c - ol[:, 1] * s
    oy = y + ol[:, 0] * s + ol[:, 1] * c
    cx, cy, ins = grid.cells(ox, oy)
    mask[cy[ins], cx[ins]] = True
    return mask


def footprint_outline(footprint, step):
    """Points along the footprint polygon's edges, robot frame (K x 2)."""
    fp = np.asarray(footprint, dtype=float)
    out = []
    for i in range(len(fp)):
        a, b = fp[i], fp[(i + 1) % len(fp)]
        n = max(1, int(math.ceil(np.hypot(*(b - a)) / step)))
        for k in range(n):
            out.append(a + (b - a) * k / n)
    return np.array(out) if out else np.zeros((1, 2))


class Trajectories:
    """N trajectories of T points: x, y, th [N, T], the sampled velocities and costs."""

    def __init__(self, vx, vy, vth, x, y, th, cost):
        self.vx, self.vy, self.vth = vx, vy, vth
        self.x, self.y, self.th = x, y, th
        self.cost = cost


class TrajectoryPlanner:
    def __init__(self, params=None, footprint=None):
        self.p = params or TrajectoryParams()
        self.footprint = footprint or []
        self.grid = None
        self.path_map = None
        self.goal_map = None
        self.impossible = None
        self.stuck_left = self.stuck_right = False
        self.rotating_left = self.rotating_right = False
        self.stuck_left_strafe = self.stuck_right_strafe = False
        self.strafe_left = self.strafe_right = False
        self.escaping = False
        self.prev_x = self.prev_y = 0.0
        self.escape_x = self.escape_y = self.escape_theta = 0.0
        self.final_goal = None

    # ---- maps --------------------------------------------------------------------------
    def update_plan(self, grid, plan_xy, robot_pose=None):
        """The local costmap snapshot and the (local-frame) plan as (x, y) pairs; the cells
        under the footprint at robot_pose (x, y, th) do not block the wavefronts (the
        original's within_robot cells)."""
        self.grid = grid
        cells = plan_cells(grid, plan_xy)
        within = None
        if robot_pose is not None:
            within = footprint_cells(grid, self.footprint, *robot_pose)
        self.path_map, self.impossible = wavefront(grid, cells, within_robot=within)
        # the local goal: the last plan cell inside the local map
        self.goal_map, _ = wavefront(grid, cells[-1:] if cells else [], within_robot=within)
        if len(plan_xy):
            self.final_goal = tuple(plan_xy[-1])

    # ---- simulation --------------------------------------------------------------------
    def simulate(self, x, y, th, vx0, vy0, vth0, samples):
        """samples: (N, 3) target velocities. Returns Trajectories with cost filled."""
        p = self.p
        samples = np.asarray(samples, dtype=float).reshape(-1, 3)
        svx, svy, svth = samples[:, 0], samples[:, 1], samples[:, 2]
        sim_dist = np.hypot(svx, svy) * p.sim_time
        sim_ang = np.abs(svth) * p.sim_time
        steps = np.maximum(np.ceil(np.maximum(sim_dist / p.sim_granularity,
                                              sim_ang / p.angular_sim_granularity)), 1)
        t_steps = int(min(max(steps.max(), 1), p.max_sim_steps))
        dt = p.sim_time / t_steps
        k = np.arange(1, t_steps)[None, :]            # velocity after k updates

        def profile(v0, target, acc):
            if p.dwa:
                return np.repeat(target[:, None], t_steps - 1, axis=1)
            diff = v0 - target[:, None]
            return target[:, None] + np.sign(diff) * np.maximum(np.abs(diff) - k * acc * dt, 0)
        vx = profile(float(vx0), svx, p.acc_lim_x)
        vy = profile(float(vy0), svy, p.acc_lim_y)
        vth = profile(float(vth0), svth, p.acc_lim_theta)
        n = len(samples)
        ths = np.empty((n, t_steps))
        ths[:, 0] = th
        ths[:, 1:] = th + np.cumsum(vth * dt, axis=1)
        c, s = np.cos(ths[:, :-1]), np.sin(ths[:, :-1])
        xs = np.empty((n, t_steps))
        ys = np.empty((n, t_steps))
        xs[:, 0] = x
        ys[:, 0] = y
        xs[:, 1:] = x + np.cumsum((vx * c - vy * s) * dt, axis=1)
        ys[:, 1:] = y + np.cumsum((vx * s + vy * c) * dt, axis=1)
        tr = Trajectories(svx, svy, svth, xs, ys, ths, None)
        self.score(tr)
        return tr

    def score(self, tr):
        g = self.grid
        p = self.p
        xs, ys = tr.x, tr.y
        px, py, pin = g.cells(xs, ys)
        pxc, pyc = np.where(pin, px, 0), np.where(pin, py, 0)
        center = np.where(pin, g.data[pyc, pxc], NO_INFORMATION).astype(np.int64)
        from . import native as _native
        fp_cost = _native.footprint_costs(g.data, g.origin_x, g.origin_y, g.resolution,
                                          np.asarray(self.footprint, dtype=float).reshape(-1, 2),
                                          xs, ys, tr.th, exact=p.exact_outline)
        illegal = ~pin.all(axis=1) | (fp_cost < 0) | ((center == LETHAL_OBSTACLE) |
                                                      (center == NO_INFORMATION)).any(axis=1)
        if len(self.footprint) < 3:
            illegal |= (center == INSCRIBED_INFLATED_OBSTACLE).any(axis=1)
        occ = np.maximum(np.where(center == NO_INFORMATION, 0, center).max(axis=1), fp_cost)
        pd = np.where(pin, self.path_map[pyc, pxc], self.impossible)
        gd = np.where(pin, self.goal_map[pyc, pxc], self.impossible)
        impossible = ((pd >= self.impossible) | (gd >= self.impossible)).any(axis=1)
        scale = g.resolution if p.meter_scoring else 1.0
        cost = (p.pdist_scale * pd[:, -1] * scale + p.gdist_scale * gd[:, -1] * scale +
                p.occdist_scale * occ)
        cost = np.where(impossible, -2.0, cost)
        cost = np.where(illegal, -1.0, cost)
        tr.cost = cost

    def resolve(self, tr, i):
        """True when trajectory i is valid."""
        return bool(tr.cost[i] >= 0)

    def best_index(self, tr):
        """The first lowest-cost valid trajectory in sampling order, or None."""
        valid = tr.cost >= 0
        if not valid.any():
            return None
        return int(np.argmin(np.where(valid, tr.cost, np.inf)))

    # ---- the choice ----------------------------------------------------------------------
    def find_best_path(self, x, y, th, vx, vy, vth):
        """(vx, vy, vth, cost, trajectory points Tx3) of the best command; cost < 0 when
        none is valid (the caller stops)."""
        p = self.p
        gx, gy = self.final_goal if self.final_goal else (x, y)
        dist_goal = math.hypot(gx - x, gy - y)
        max_vel_x = max(min(p.max_vel_x, dist_goal / p.sim_time), p.min_vel_x)
        if p.dwa:
            max_vx = max(min(max_vel_x, vx + p.acc_lim_x * p.sim_period), p.min_vel_x)
            min_vx = max(p.min_vel_x, vx - p.acc_lim_x * p.sim_period)
            max_vth = min(p.max_vel_theta, vth + p.acc_lim_theta * p.sim_period)
            min_vth = max(p.min_vel_theta, vth - p.acc_lim_theta * p.sim_period)
        else:
            max_vx = max(min(max_vel_x, vx + p.acc_lim_x * p.sim_time), p.min_vel_x)
            min_vx = max(p.min_vel_x, vx - p.acc_lim_x * p.sim_time)
            max_vth = min(p.max_vel_theta, vth + p.acc_lim_theta * p.sim_time)
            min_vth = max(p.min_vel_theta, vth - p.acc_lim_theta * p.sim_time)
        nvx = max(int(p.vx_samples), 1)
        nvth = max(int(p.vtheta_samples), 1)
        vxs = np.linspace(min_vx, max_vx, nvx) if nvx > 1 else np.array([min_vx])
        vths = np.linspace(min_vth, max_vth, nvth) if nvth > 1 else np.array([min_vth])
        dvth = (max_vth - min_vth) / max(nvth - 1, 1)
        best = None
        if not self.escaping:
            # per vx (min .. max): straight first, then vtheta from min_vth in nvth - 1 steps
            vth_row = np.concatenate([[0.0], min_vth + dvth * np.arange(nvth - 1)])
            gv, gt = np.meshgrid(vxs, vth_row, indexing='ij')
            fwd = np.stack([gv.ravel(), np.zeros(gv.size), gt.ravel()], axis=1)
            tr = self.simulate(x, y, th, vx, vy, vth, fwd)
            i = self.best_index(tr)
            if i is not None:
                best = (tr.vx[i], 0.0, tr.vth[i], tr.cost[i], tr, i)
            # rotations in place, towards open space (heading_lookahead)
            rot = np.array([v if abs(v) > 1e-9 else 0.0 for v in vths])
            rot = np.where(rot > 0, np.maximum(rot, p.min_in_place_vel_theta),
                           np.minimum(rot, -p.min_in_place_vel_theta))
            rsamples = np.stack([np.zeros(len(rot)), np.zeros(len(rot)), rot], axis=1)
            rt = self.simulate(x, y, th, vx, vy, vth, rsamples)
            heading_dist = None
            for i, vsamp in enumerate(vths):
                c = rt.cost[i]
                if c < 0 or not (vsamp > dvth or vsamp < -dvth):
                    continue
                if best is not None and c > best[3]:
                    continue
                if not self.resolve(rt, i):
                    continue
                ex, ey, eth = rt.x[i, -1], rt.y[i, -1], rt.th[i, -1]
                ax, ay = ex + p.heading_lookahead * math.cos(eth), \
                    ey + p.heading_lookahead * math.sin(eth)
                cxs, cys, inside = self.grid.cells(np.array([ax]), np.array([ay]))
                if not inside[0]:
                    continue
                ahead = self.goal_map[cys[0], cxs[0]]
                if heading_dist is None or ahead < heading_dist:
                    if (vsamp < 0 and not self.stuck_left) or (vsamp > 0 and not self.stuck_right):
                        best = (0.0, 0.0, rt.vth[i], c, rt, i)
                        heading_dist = ahead
        if best is not None and best[3] >= 0:
            bvx, bvy, bvth = best[0], best[1], best[2]
            self._update_oscillation_flags(x, y, th, bvx, bvy, bvth)
            tr, i = best[4], best[5]
            pts = np.stack([tr.x[i], tr.y[i], tr.th[i]], axis=1)
            return bvx, bvy, bvth, best[3], pts
        # nothing legal: back up slowly, even when the map shows it as blocked (the original:
        # a footprint already touching an obstacle makes every trajectory illegal, -1); only
        # a backward trajectory with no route to the plan (-2) fails
        tr = self.simulate(x, y, th, vx, vy, vth, [[p.escape_vel, 0.0, 0.0]])
        cost = float(tr.cost[0])
        if not self.escaping and cost > -2.0:
            self.escaping = True
            self.escape_x, self.escape_y, self.escape_theta = x, y, th
        self._check_escape(x, y, th)
        if cost == -1.0:
            cost = 1.0
        if cost < 0:
            return 0.0, 0.0, 0.0, cost, np.zeros((0, 3))
        pts = np.stack([tr.x[0], tr.y[0], tr.th[0]], axis=1)
        return p.escape_vel, 0.0, 0.0, cost, pts

    def _check_escape(self, x, y, th):
        p = self.p
        if self.escaping and (math.hypot(x - self.escape_x, y - self.escape_y) >
                              p.escape_reset_dist or
                              abs(_angle(th - self.escape_theta)) > p.escape_reset_theta):
            self.escaping = False

    def reset_oscillation_flags(self):
        self.rotating_left = self.rotating_right = False
        self.stuck_left = self.stuck_right = False

    def _update_oscillation_flags(self, x, y, th, vx, vy, vth):
        """This package's flags (see README): a flip of the in-place turn direction bars the
        direction turned to, a second flip bars both (forward arcs only); everything is
        released once the robot is more than oscillation_reset_dist from where it last turned
        in place (the original's reference point). The release used to compare consecutive
        forward cycles instead: more than 0.05 m per 0.1 s cycle needs 0.5 m/s, above what
        the space scanner drives, so once barred the turns stayed barred for good (into the
        following goals: loops at min_vel_x where a turn in place was due)."""
        p = self.p
        if self.escaping:
            self._check_escape(x, y, th)
        if vx == 0 and vth < 0:
            self.stuck_left = self.stuck_left or self.rotating_left
            self.rotating_right = True
            self.prev_x, self.prev_y = x, y
        elif vx == 0 and vth > 0:
            self.stuck_right = self.stuck_right or self.rotating_right
            self.rotating_left = True
            self.prev_x, self.prev_y = x, y
        if math.hypot(x - self.prev_x, y - self.prev_y) > p.oscillation_reset_dist:
            self.reset_oscillation_flags()

    def check_trajectory(self, x, y, th, vx, vy, vth, vx_samp, vy_samp, vth_samp):
        """True when the sampled command is legal (the original's checkTrajectory)."""
        tr = self.simulate(x, y, th, vx, vy, vth, [[vx_samp, vy_samp, vth_samp]])
        return self.resolve(tr, 0)


def _toward(v, target, step):
    return np.where(v < target, np.minimum(target, v + step), np.maximum(target, v - step))


def _angle(a):
    return math.atan2(math.sin(a), math.cos(a))
