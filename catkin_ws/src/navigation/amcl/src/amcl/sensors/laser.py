"""Laser models (amcl's AMCLLaser): 'likelihood_field' (default), 'beam' and
'likelihood_field_prob' (with optional beam skipping). Each returns the new particle weights,
vectorised over particles x beams.

As the original, a particle's factor is 1 + sum(pz^3) for the beam and likelihood_field models
(an ad-hoc but robust combination) and exp(sum(log pz)) for likelihood_field_prob."""
from dataclasses import dataclass

import numpy as np

LASER_MODELS = ('likelihood_field', 'beam', 'likelihood_field_prob')


@dataclass
class LaserData:
    """One scan in the robot's base frame: ranges (B,), bearings (B,) relative to the laser's
    x axis, range_max, and the laser's pose (x, y, yaw) on the robot."""
    ranges: np.ndarray
    angles: np.ndarray
    range_max: float
    laser_pose: tuple = (0.0, 0.0, 0.0)


class LaserModel:
    def __init__(self, model_type='likelihood_field', max_beams=30, z_hit=0.95, z_short=0.1,
                 z_max=0.05, z_rand=0.05, sigma_hit=0.2, lambda_short=0.1, chi_outlier=0.0,
                 do_beamskip=False, beam_skip_distance=0.5, beam_skip_threshold=0.3,
                 beam_skip_error_threshold=0.9):
        if model_type not in LASER_MODELS:
            raise ValueError('unknown laser_model_type "%s" (one of %s)' % (model_type, ', '.join(LASER_MODELS)))
        if max_beams < 2:
            raise ValueError('laser_max_beams must be >= 2, got %r' % (max_beams,))
        self.model_type = model_type
        self.max_beams = int(max_beams)
        self.z_hit, self.z_short, self.z_max, self.z_rand = z_hit, z_short, z_max, z_rand
        self.sigma_hit, self.lambda_short, self.chi_outlier = sigma_hit, lambda_short, chi_outlier
        self.do_beamskip = do_beamskip
        self.beam_skip_distance = beam_skip_distance
        self.beam_skip_threshold = beam_skip_threshold
        self.beam_skip_error_threshold = beam_skip_error_threshold

    def beam_indices(self, count):
        """The beams used: every step-th with step = (count - 1) // (max_beams - 1), >= 1."""
        step = max(1, (count - 1) // (self.max_beams - 1))
        return np.arange(0, count, step)[:self.max_beams]

    def _endpoints(self, poses, data, idx):
        """Laser poses of all particles and the world bearings of the used beams (N, B)."""
        lx, ly, lth = data.laser_pose
        c, s = np.cos(poses[:, 2]), np.sin(poses[:, 2])
        px = poses[:, 0] + c * lx - s * ly
        py = poses[:, 1] + s * lx + c * ly
        pth = poses[:, 2] + lth
        bearing = pth[:, None] + data.angles[idx][None, :]
        return px, py, bearing

    def weights(self, gmap, poses, weights, data):
        """New (unnormalised) weights for particles poses (N, 3) with weights (N,)."""
        idx = self.beam_indices(len(data.ranges))
        if self.model_type == 'beam':
            factor = self._beam(gmap, poses, data, idx)
        elif self.model_type == 'likelihood_field':
            factor = self._likelihood_field(gmap, poses, data, idx)
        else:
            factor = self._likelihood_field_prob(gmap, poses, data, idx)
        return weights * factor

    def _beam(self, gmap, poses, data, idx):
        obs = data.ranges[idx]
        keep = np.isfinite(obs)
        idx, obs = idx[keep], obs[keep]
        px, py, bearing = self._endpoints(poses, data, idx)
        map_range = gmap.calc_range(px[:, None], py[:, None], bearing, data.range_max)
        z = obs[None, :] - map_range
        pz = self.z_hit * np.exp(-(z * z) / (2 * self.sigma_hit ** 2))
        pz = pz + np.where(z < 0, self.z_short * self.lambda_short * np.exp(-self.lambda_short * obs[None, :]), 0.0)
        pz = pz + np.where(obs[None, :] >= data.range_max, self.z_max, 0.0)
        pz = pz + np.where(obs[None, :] < data.range_max, self.z_rand / data.range_max, 0.0)
        return 1.0 + np.sum(pz ** 3, axis=1)

    def _hits(self, gmap, poses, data, idx):
        obs = data.ranges[idx]
        keep = np.isfinite(obs) & (obs < data.range_max)      # max-range readings carry no hit
        idx, obs = idx[keep], obs[keep]
        px, py, bearing = self._endpoints(poses, data, idx)
        hx = px[:, None] + obs[None, :] * np.cos(bearing)
        hy = py[:, None] + obs[None, :] * np.sin(bearing)
        return gmap.occ_dist_at(hx, hy)

    def _likelihood_field(self, gmap, poses, data, idx):
        z, _ = self._hits(gmap, poses, data, idx)
        pz = self.z_hit * np.exp(-(z * z) / (2 * self.sigma_hit ** 2)) + self.z_rand / data.range_max
        return 1.0 + np.sum(pz ** 3, axis=1)

    def _likelihood_field_prob(self, gmap, poses, data, idx):
        z, inside = self._hits(gmap, poses, data, idx)
        denom = 2 * self.sigma_hit ** 2
        max_dist_prob = np.exp(-(gmap.max_occ_dist ** 2) / denom)
        pz = np.where(inside, self.z_hit * np.exp(-(z * z) / denom), self.z_hit * max_dist_prob)
        pz = pz + self.z_rand / data.range_max
        logp = np.log(pz)
        if self.do_beamskip and z.shape[1] > 0:
            # beams most particles agree on (a hit within beam_skip_distance) are used; the
            # rest may be unmapped obstacles. Too many skipped beams: the filter has diverged,
            # use them all.
            agree = np.mean(inside & (z < self.beam_skip_distance), axis=0)
            use = agree >= self.beam_skip_threshold
            if np.mean(~use) <= self.beam_skip_error_threshold:
                logp = logp[:, use]
        return np.exp(np.sum(logp, axis=1))
