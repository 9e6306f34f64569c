"""amcl's update logic without ROS (the part of amcl_node.cpp that is not messaging): when to
run the motion and laser updates (update_min_d / update_min_a, forced no-motion updates),
resample_interval, the pose hypothesis and the map -> odom correction. Used by the node and
the benchmark."""
from dataclasses import dataclass, field

import numpy as np

from .map import Map
from .pf import ParticleFilter
from .sensors import LaserData, LaserModel, OdomModel, angle_diff, normalize


@dataclass
class Config:
    """Every filter parameter of amcl with the original's default."""
    min_particles: int = 100
    max_particles: int = 5000
    kld_err: float = 0.01
    kld_z: float = 0.99
    update_min_d: float = 0.2
    update_min_a: float = np.pi / 6.0
    resample_interval: int = 2
    recovery_alpha_slow: float = 0.001
    recovery_alpha_fast: float = 0.1
    selective_resampling: bool = False
    laser_model_type: str = 'likelihood_field'
    laser_max_beams: int = 30
    laser_z_hit: float = 0.95
    laser_z_short: float = 0.1
    laser_z_max: float = 0.05
    laser_z_rand: float = 0.05
    laser_sigma_hit: float = 0.2
    laser_lambda_short: float = 0.1
    laser_likelihood_max_dist: float = 2.0
    do_beamskip: bool = False
    beam_skip_distance: float = 0.5
    beam_skip_threshold: float = 0.3
    beam_skip_error_threshold: float = 0.9
    odom_model_type: str = 'diff'
    odom_alpha1: float = 0.2
    odom_alpha2: float = 0.2
    odom_alpha3: float = 0.2
    odom_alpha4: float = 0.2
    odom_alpha5: float = 0.2
    initial_pose: tuple = (0.0, 0.0, 0.0)
    initial_cov: tuple = (0.5 * 0.5, 0.5 * 0.5, (np.pi / 12.0) ** 2)


def compose(a, b):
    """2-D pose composition a (+) b."""
    c, s = np.cos(a[2]), np.sin(a[2])
    return np.array([a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], normalize(a[2] + b[2])])


def inverse(a):
    c, s = np.cos(a[2]), np.sin(a[2])
    return np.array([-c * a[0] - s * a[1], s * a[0] - c * a[1], normalize(-a[2])])


@dataclass
class Result:
    updated: bool = False            # the filter ran a laser update on this scan
    resampled: bool = False
    pose: np.ndarray = None          # best hypothesis (x, y, yaw) in the map
    cov: np.ndarray = None           # (3, 3): the whole set's covariance, as amcl publishes
    map_to_odom: np.ndarray = None   # (x, y, yaw)
    stats: dict = field(default_factory=dict)


class Localizer:
    def __init__(self, config=None, rng=None):
        self.config = config or Config()
        self.rng = rng if rng is not None else np.random.default_rng()
        c = self.config
        self.odom = OdomModel(c.odom_model_type, c.odom_alpha1, c.odom_alpha2, c.odom_alpha3,
                              c.odom_alpha4, c.odom_alpha5, rng=self.rng)
        self.laser = LaserModel(c.laser_model_type, c.laser_max_beams, c.laser_z_hit, c.laser_z_short,
                                c.laser_z_max, c.laser_z_rand, c.laser_sigma_hit, c.laser_lambda_short,
                                do_beamskip=c.do_beamskip, beam_skip_distance=c.beam_skip_distance,
                                beam_skip_threshold=c.beam_skip_threshold,
                                beam_skip_error_threshold=c.beam_skip_error_threshold)
        self.map = None
        self.pf = None
        self.pf_init = False            # odometric reference pose taken
        self.pf_odom_pose = None
        self.force_update = False
        self.resample_count = 0
        self.map_to_odom = None

    # -- map and initialisation ---------------------------------------------------------
    def set_map(self, gmap: Map, initial_pose=None, initial_cov=None):
        """New map: likelihood field, a fresh filter at the initial pose."""
        self.map = gmap
        if self.config.laser_model_type != 'beam':
            gmap.update_cspace(self.config.laser_likelihood_max_dist)
        c = self.config
        self.pf = ParticleFilter(c.min_particles, c.max_particles, c.recovery_alpha_slow,
                                 c.recovery_alpha_fast, c.kld_err, c.kld_z, self.uniform_poses,
                                 c.selective_resampling, rng=self.rng)
        self.set_initial_pose(initial_pose if initial_pose is not None else c.initial_pose,
                              initial_cov if initial_cov is not None else c.initial_cov)

    def set_initial_pose(self, mean, cov):
        """mean (x, y, yaw); cov: (var_x, var_y, var_yaw) or a (3, 3) matrix."""
        cov = np.asarray(cov, dtype=float)
        if cov.shape == (3,):
            cov = np.diag(cov)
        self.pf.init(np.asarray(mean, dtype=float), cov)
        self.pf_init = False

    def uniform_poses(self, n):
        """n poses uniform over the map's free cells (cell centres), yaw uniform."""
        free = self.map.free_cells
        if not len(free):
            raise ValueError('the map has no free cells')
        pick = free[self.rng.integers(0, len(free), n)]
        x, y = self.map.map_to_world(pick[:, 0], pick[:, 1])
        return np.stack([x, y, self.rng.uniform(-np.pi, np.pi, n)], axis=1)

    def global_localization(self):
        self.pf.init_model(self.uniform_poses)
        self.pf_init = False

    def request_nomotion_update(self):
        self.force_update = True

    # -- the scan update ------------------------------------------------------------------
    def process(self, odom_pose, data: LaserData):
        """One scan with the robot's odometric pose (x, y, yaw) at its stamp."""
        odom_pose = np.asarray(odom_pose, dtype=float)
        res = Result()
        c = self.config
        if not self.pf_init:
            self.pf_odom_pose = odom_pose.copy()
            self.pf_init = True
            update = True
            self.resample_count = 0
        else:
            delta = np.array([odom_pose[0] - self.pf_odom_pose[0], odom_pose[1] - self.pf_odom_pose[1],
                              float(angle_diff(odom_pose[2], self.pf_odom_pose[2]))])
            update = (abs(delta[0]) > c.update_min_d or abs(delta[1]) > c.update_min_d
                      or abs(delta[2]) > c.update_min_a or self.force_update)
            self.force_update = False
            if update:
                self.pf.update_action(lambda poses: self.odom.sample(poses, odom_pose, delta))
                self.pf_odom_pose = odom_pose.copy()
        if update:
            self.pf.update_sensor(lambda poses, w: self.laser.weights(self.map, poses, w, data))
            self.resample_count += 1
            if self.resample_count % c.resample_interval == 0:
                self.pf.update_resample()
                res.resampled = True
            else:
                self.pf.cluster_stats()
            best = self.pf.best_cluster()
            res.updated = True
            res.pose = best.mean.copy()
            res.cov = self.pf.cov.copy()
            self.map_to_odom = compose(res.pose, inverse(odom_pose))
            res.stats = {'particles': self.pf.count, 'clusters': len(self.pf.clusters)}
        res.map_to_odom = None if self.map_to_odom is None else self.map_to_odom.copy()
        return res

    def estimate(self):
        best = self.pf.best_cluster()
        return best.mean.copy(), self.pf.cov.copy()
