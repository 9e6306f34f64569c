"""Adaptive (KLD-sampling) particle filter over (x, y, yaw), as amcl's pf.c:

- the sample count after resampling follows Fox's KLD bound over a histogram of
  0.5 m x 0.5 m x 10 deg bins, clamped to [min_particles, max_particles];
- recovery: short- and long-term averages of the measurement likelihood (alpha_fast,
  alpha_slow); while the short-term one is below the long-term one, resampling injects a
  fraction max(0, 1 - w_fast / w_slow) of random poses;
- clusters: connected histogram bins, each with its weight, mean and covariance; the pose
  estimate is the heaviest cluster's mean.

Particles are rows of a (N, 3) array with a (N,) weight array; the functions that draw random
poses, the motion and the measurement models are passed in (no ROS, no map here)."""
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

BIN_SIZE = (0.5, 0.5, np.radians(10.0))


def resample_limit(k, pop_err, pop_z, min_samples, max_samples):
    """Samples needed for k occupied bins (Fox 2003; amcl's pf_resample_limit, which, as the
    original, takes kld_z itself as the normal quantile)."""
    if k <= 1:
        return max_samples
    b = 2.0 / (9.0 * (k - 1))
    x = 1.0 - b + np.sqrt(b) * pop_z
    n = int(np.ceil((k - 1) / (2.0 * pop_err) * x ** 3))
    return int(min(max(n, min_samples), max_samples))


def resample_limits(k, pop_err, pop_z, min_samples, max_samples):
    """resample_limit for an array of bin counts."""
    k = np.asarray(k, dtype=float)
    km1 = np.maximum(k - 1, 1.0)
    b = 2.0 / (9.0 * km1)
    x = 1.0 - b + np.sqrt(b) * pop_z
    n = np.ceil(km1 / (2.0 * pop_err) * x ** 3)
    n = np.clip(n, min_samples, max_samples).astype(np.int64)
    return np.where(k <= 1, max_samples, n)


def histogram_bins(poses):
    """Integer bin keys (N, 3) of the KLD histogram."""
    return np.floor(poses / np.asarray(BIN_SIZE)).astype(np.int64)


def _normalize(a):
    return (a + np.pi) % (2.0 * np.pi) - np.pi


@dataclass
class Cluster:
    weight: float
    mean: np.ndarray      # (3,)
    cov: np.ndarray       # (3, 3)
    count: int


def weighted_stats(poses, w):
    """Weighted mean (circular for yaw) and covariance (x, y block, yaw as amcl:
    -2 log |mean unit vector|)."""
    total = w.sum()
    if total <= 0:
        w = np.full(len(w), 1.0 / len(w))
        total = 1.0
    w = w / total
    mx = np.dot(w, poses[:, 0])
    my = np.dot(w, poses[:, 1])
    c = np.dot(w, np.cos(poses[:, 2]))
    s = np.dot(w, np.sin(poses[:, 2]))
    mean = np.array([mx, my, np.arctan2(s, c)])
    cov = np.zeros((3, 3))
    dx, dy = poses[:, 0] - mx, poses[:, 1] - my
    cov[0, 0] = np.dot(w, dx * dx)
    cov[0, 1] = cov[1, 0] = np.dot(w, dx * dy)
    cov[1, 1] = np.dot(w, dy * dy)
    cov[2, 2] = -2.0 * np.log(max(np.hypot(c, s), 1e-300))
    return mean, cov


class ParticleFilter:
    def __init__(self, min_samples=100, max_samples=5000, alpha_slow=0.001, alpha_fast=0.1,
                 pop_err=0.01, pop_z=0.99, random_pose=None, selective_resampling=False, rng=None):
        if min_samples > max_samples:
            raise ValueError('min_particles (%d) > max_particles (%d)' % (min_samples, max_samples))
        if min_samples < 1:
            raise ValueError('min_particles must be >= 1, got %d' % min_samples)
        self.min_samples, self.max_samples = int(min_samples), int(max_samples)
        self.alpha_slow, self.alpha_fast = alpha_slow, alpha_fast
        self.pop_err, self.pop_z = pop_err, pop_z
        self.random_pose = random_pose      # f(n) -> (n, 3) poses, for recovery
        self.selective_resampling = selective_resampling
        self.rng = rng if rng is not None else np.random.default_rng()
        self.w_slow = 0.0
        self.w_fast = 0.0
        self.poses = np.zeros((max_samples, 3))
        self.weights = np.full(max_samples, 1.0 / max_samples)
        self.clusters = []
        self.mean = np.zeros(3)
        self.cov = np.zeros((3, 3))
        self.converged = False

    @property
    def count(self):
        return len(self.weights)

    # -- initialisation -------------------------------------------------------------------
    def init(self, mean, cov):
        """max_samples particles from a Gaussian (mean (3,), cov (3, 3))."""
        mean = np.asarray(mean, dtype=float)
        cov = np.asarray(cov, dtype=float)
        n = self.max_samples
        # amcl's pf_pdf_gaussian: eigen-decomposition, independent normals along the axes
        vals, vecs = np.linalg.eigh(cov)
        z = self.rng.normal(size=(n, 3)) * np.sqrt(np.maximum(vals, 0.0))
        poses = mean + z @ vecs.T
        poses[:, 2] = _normalize(poses[:, 2])
        self._set(poses)

    def init_model(self, fn):
        """max_samples particles from fn(n) (global localization: uniform over free space)."""
        self._set(np.asarray(fn(self.max_samples), dtype=float))

    def _set(self, poses):
        self.poses = poses
        self.weights = np.full(len(poses), 1.0 / len(poses))
        self.w_slow = self.w_fast = 0.0
        self.converged = False
        self.cluster_stats()

    # -- updates --------------------------------------------------------------------------
    def update_action(self, fn):
        """Apply the motion model fn(poses) in place."""
        fn(self.poses)

    def update_sensor(self, fn):
        """Reweight with fn(poses, weights) -> new weights; update w_slow / w_fast."""
        w = np.asarray(fn(self.poses, self.weights), dtype=float)
        total = float(w.sum())
        if total > 0 and np.isfinite(total):
            self.weights = w / total
            w_avg = total / self.count
            if self.w_slow == 0.0:
                self.w_slow = w_avg
            else:
                self.w_slow += self.alpha_slow * (w_avg - self.w_slow)
            if self.w_fast == 0.0:
                self.w_fast = w_avg
            else:
                self.w_fast += self.alpha_fast * (w_avg - self.w_fast)
        else:
            self.weights = np.full(self.count, 1.0 / self.count)
        return total

    def n_effective(self):
        return 1.0 / float(np.sum(self.weights ** 2))

    def update_resample(self):
        """KLD-sampling resample with recovery; returns the new sample count."""
        if self.selective_resampling and self.n_effective() > self.count / 2.0:
            return self.count
        w_diff = 1.0 - self.w_fast / self.w_slow if self.w_slow > 0 else 0.0
        w_diff = max(0.0, w_diff)
        n = self.max_samples
        # draw max_samples candidates (roulette on the cumulative weights, random poses with
        # probability w_diff), then keep the prefix the KLD bound asks for
        cdf = np.cumsum(self.weights)
        cdf[-1] = 1.0
        picks = np.searchsorted(cdf, self.rng.random(n), side='right')
        picks = np.minimum(picks, self.count - 1)
        new = self.poses[picks].copy()
        if w_diff > 0 and self.random_pose is not None:
            rand = self.rng.random(n) < w_diff
            if rand.any():
                new[rand] = self.random_pose(int(rand.sum()))
        keys = histogram_bins(new)
        _, first = np.unique(keys, axis=0, return_index=True)
        is_new_bin = np.zeros(n, dtype=bool)
        is_new_bin[first] = True
        k = np.cumsum(is_new_bin)           # occupied bins after each sample
        limits = resample_limits(k, self.pop_err, self.pop_z, self.min_samples, self.max_samples)
        count = np.arange(1, n + 1)
        # as pf.c: stop after the sample that takes the count above the limit
        over = np.nonzero(count > limits)[0]
        m = int(over[0]) + 1 if over.size else n
        m = max(m, self.min_samples)
        self.poses = new[:m]
        self.weights = np.full(m, 1.0 / m)
        if w_diff > 0:
            self.w_slow = self.w_fast = 0.0
        self.cluster_stats()
        return m

    # -- statistics -----------------------------------------------------------------------
    def cluster_stats(self):
        """Clusters of connected histogram bins (26-neighbourhood), heaviest first; the
        overall weighted mean and covariance."""
        keys = histogram_bins(self.poses)
        lo = keys.min(axis=0)
        shape = keys.max(axis=0) - lo + 1
        if int(np.prod(shape)) > 20_000_000:      # scattered far beyond any map: one cluster
            self.mean, self.cov = weighted_stats(self.poses, self.weights)
            self.clusters = [Cluster(1.0, self.mean, self.cov, self.count)]
            return self.clusters
        grid = np.zeros(shape, dtype=bool)
        rel = keys - lo
        grid[rel[:, 0], rel[:, 1], rel[:, 2]] = True
        labels, nlab = ndimage.label(grid, structure=np.ones((3, 3, 3)))
        lab = labels[rel[:, 0], rel[:, 1], rel[:, 2]] - 1
        self.clusters = []
        order = np.argsort(lab, kind='stable')
        bounds = np.searchsorted(lab[order], np.arange(nlab + 1))
        for c in range(nlab):
            members = order[bounds[c]:bounds[c + 1]]
            w = self.weights[members]
            mean, cov = weighted_stats(self.poses[members], w)
            self.clusters.append(Cluster(float(w.sum()), mean, cov, len(members)))
        self.clusters.sort(key=lambda cl: -cl.weight)
        self.mean, self.cov = weighted_stats(self.poses, self.weights)
        return self.clusters

    def best_cluster(self):
        return self.clusters[0] if self.clusters else Cluster(1.0, self.mean, self.cov, self.count)
