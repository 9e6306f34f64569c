"""GridSlam: gmapping's Rao-Blackwellized particle filter (GridSlamProcessor::processScan).

Every particle carries its own occupancy grid (hit/visit counts, grown on demand inside
xmin..xmax) and a trajectory in a shared ancestry tree. Poses are LASER poses (the frame the scan
is measured in) in the map frame; odometry is the laser pose in the odom frame."""
import math

import numpy as np

from gmapping import native
from gmapping.motion import absolute_difference, draw_from_motion
from gmapping.resample import entropy, low_variance_indices, neff, normalize_log_weights

FULLNESS_THRESHOLD = 0.1      # gmapping ScanMatcher m_fullnessThreshold
NULL_LIKELIHOOD = -0.5        # gmapping ScanMatcher m_likelihood null
MARGIN = 2.0                  # m of grid added around a scan when the grids grow


class GridSlam(object):
    def __init__(self, params, seed=None):
        self.p = params
        self.rng = np.random.default_rng(seed)
        self.n = int(params.particles)
        self.delta = float(params.delta)
        self.poses = None             # (n, 3) laser poses in the map frame
        self.log_w = np.zeros(self.n)          # log likelihood accumulated since the last resampling
        self.weight_sum = np.zeros(self.n)     # accumulated over the lineage (best particle choice)
        self.weights = np.full(self.n, 1.0 / self.n)
        self.node_of = np.zeros(self.n, dtype=np.int64)
        self.tree_pose, self.tree_parent, self.tree_stamp = [], [], []
        self.grids = None             # native.Grids; origin a multiple of delta from (xmin, ymin)
        self.odom = None
        self.last_processed = None    # odometry pose and stamp of the last processed scan
        self.linear = self.angular = 0.0
        self.count = 0                # processed scans
        self.resamples = 0
        self.neff = float(self.n)
        self.scan_c = None
        self.matcher = native.GmMatcherParams(
            params.sigma, int(params.kernelSize), params.lsigma, int(params.lskip), params.lstep,
            params.astep, int(params.iterations), FULLNESS_THRESHOLD, NULL_LIKELIHOOD, params.minimumScore)

    # --- grids -----------------------------------------------------------------------------
    def _ensure_extent(self, poses, reach):
        """Grow every particle's grid so that circles of radius reach around poses fit."""
        d = self.delta
        x0 = max(poses[:, 0].min() - reach, self.p.xmin)
        x1 = min(poses[:, 0].max() + reach, self.p.xmax)
        y0 = max(poses[:, 1].min() - reach, self.p.ymin)
        y1 = min(poses[:, 1].max() + reach, self.p.ymax)
        if self.grids is not None:
            h, w = self.grids.shape[1:]
            ox, oy = self.grids.origin
            if x0 >= ox and y0 >= oy and x1 < ox + w * d and y1 < oy + h * d:
                return
            x0, y0 = min(x0 - MARGIN, ox), min(y0 - MARGIN, oy)
            x1, y1 = max(x1 + MARGIN, ox + w * d), max(y1 + MARGIN, oy + h * d)
        # snap to the published map's cell lattice (origin xmin, ymin)
        cx0 = int(math.floor((max(x0, self.p.xmin) - self.p.xmin) / d))
        cy0 = int(math.floor((max(y0, self.p.ymin) - self.p.ymin) / d))
        cx1 = int(math.ceil((min(x1, self.p.xmax) - self.p.xmin) / d)) + 1
        cy1 = int(math.ceil((min(y1, self.p.ymax) - self.p.ymin) / d)) + 1
        new_origin = (self.p.xmin + cx0 * d, self.p.ymin + cy0 * d)
        grids = native.Grids(self.n, cy1 - cy0, cx1 - cx0, new_origin, d)
        if self.grids is not None:
            ox = int(round((self.grids.origin[0] - new_origin[0]) / d))
            oy = int(round((self.grids.origin[1] - new_origin[1]) / d))
            h, w = self.grids.shape[1:]
            for new, old in zip(grids.cells, self.grids.cells):    # as raw 12-byte cells (memcpy)
                new.view('V12')[oy:oy + h, ox:ox + w] = old.view('V12')
        self.grids = grids

    def _register(self, scan, reach):
        self._ensure_extent(self.poses, reach)
        native.integrate(self.grids, self._clamped(self.poses), scan)

    def _clamped(self, poses):
        """Poses kept inside xmin..xmax (a beam leaving the configured map is cut by the grid)."""
        out = poses.copy()
        out[:, 0] = np.clip(out[:, 0], self.p.xmin + self.delta, self.p.xmax - self.delta)
        out[:, 1] = np.clip(out[:, 1], self.p.ymin + self.delta, self.p.ymax - self.delta)
        return out

    # --- filter ------------------------------------------------------------------------------
    def _add_nodes(self, stamp):
        base = len(self.tree_pose)
        for i in range(self.n):
            self.tree_pose.append(tuple(self.poses[i]))
            self.tree_parent.append(int(self.node_of[i]) if self.count > 0 else -1)
            self.tree_stamp.append(stamp)
        self.node_of = base + np.arange(self.n)

    def process(self, odom_pose, ranges, angles, max_range, max_urange, stamp):
        """Feed one scan with the laser's odometry pose (x, y, theta). Returns True if the scan was
        processed (the filter updated), False if the robot had not moved enough."""
        odom_pose = np.asarray(odom_pose, dtype=np.float64)
        ranges = np.asarray(ranges, dtype=np.float64)
        # beams beyond max_urange are clipped by the matcher; max_range drops them entirely
        scan = native.Scan(ranges, angles, max_range, max_urange)
        valid = ranges[np.isfinite(ranges) & (ranges > 0.0) & (ranges <= max_range)]
        reach = min(float(valid.max()) if valid.size else 0.0, max_urange) + 2 * self.delta
        if self.poses is None:
            self.poses = np.repeat(odom_pose[None, :], self.n, axis=0)
            self.odom = odom_pose
        # motion model on every reading (gmapping applies it before deciding to process)
        if np.any(odom_pose != self.odom):
            self.poses = draw_from_motion(self.poses, self.odom, odom_pose, self.p.srr, self.p.srt,
                                          self.p.str, self.p.stt, self.rng)
        move = absolute_difference(odom_pose, self.odom)
        self.linear += math.hypot(move[0], move[1])
        self.angular += abs(move[2])
        self.odom = odom_pose
        due = (self.count == 0 or self.linear >= self.p.linearUpdate or self.angular >= self.p.angularUpdate
               or (self.p.temporalUpdate > 0.0 and self.last_processed is not None
                   and stamp - self.last_processed >= self.p.temporalUpdate))
        if not due:
            return False
        self.linear = self.angular = 0.0
        self.last_processed = stamp
        if self.count == 0:
            self._register(scan, reach)
        else:
            self._ensure_extent(self.poses, reach)
            poses, _scores, lik = native.optimize(self.grids, self._clamped(self.poses), scan, self.matcher)
            self.poses = poses
            self.log_w += lik
            self.weight_sum += lik
            self.weights = normalize_log_weights(self.log_w, self.p.ogain)
            self.neff = neff(self.weights)
            if self.neff < self.p.resampleThreshold * self.n:
                idx = low_variance_indices(self.weights, self.rng)
                self.poses = self.poses[idx]
                self.grids = self.grids.select(idx)
                self.node_of = self.node_of[idx]
                self.weight_sum = self.weight_sum[idx]
                self.log_w = np.zeros(self.n)
                self.weights = np.full(self.n, 1.0 / self.n)
                self.resamples += 1
            self._register(scan, reach)
        self._add_nodes(stamp)
        self.count += 1
        return True

    # --- results -----------------------------------------------------------------------------
    def best_index(self):
        return int(np.argmax(self.weight_sum))

    def best_pose(self):
        return self.poses[self.best_index()].copy()

    def weight_entropy(self):
        return entropy(self.weights)

    def best_trajectory(self):
        """[(stamp, (x, y, theta))] of the best particle's processed scans, oldest first."""
        out = []
        k = int(self.node_of[self.best_index()]) if self.tree_pose else -1
        while k >= 0:
            out.append((self.tree_stamp[k], self.tree_pose[k]))
            k = self.tree_parent[k]
        return out[::-1]

    def occupancy(self, occ_thresh=None):
        """Best particle's grid -> (int8 (h, w): -1 unknown, 0 free, 100 occupied; origin (x, y))."""
        if self.grids is None:
            return None, None
        thresh = self.p.occ_thresh if occ_thresh is None else occ_thresh
        cells = self.grids.cells[self.best_index()]
        hits, visits = cells['hits'].astype(np.float32), cells['visits']
        grid = np.full(visits.shape, -1, dtype=np.int8)
        seen = visits > 0
        occ = np.zeros(visits.shape, dtype=np.float32)
        occ[seen] = hits[seen] / visits[seen]
        grid[seen] = 0
        grid[seen & (occ > thresh)] = 100
        return grid, self.grids.origin
