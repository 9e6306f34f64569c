"""The maths of Gazebo classic's ray sensor (sensors::RaySensor over physics::MultiRayShape,
ODE) and of gazebo_ros_laser, which turns its scan into a sensor_msgs/LaserScan.

`LaserModel(sensor_params)` holds a <sensor type="ray"> (or "gpu_ray") description;
`.directions` are its rays in the sensor frame, `.scan(caster, sensor_pose)` casts them and
`.to_ranges(distances, retro)` turns raw hit distances into the published ranges and
intensities. ode_sim.ros.convert.fill_laserscan() fills the ROS message.

Rules, with where they come from (gazebo-classic, gazebo11 era unless noted):

Rays (MultiRayShape::Init)
  * `samples` rays horizontally, yaw_i = min_angle + i (max_angle - min_angle) / (samples - 1),
    both ends included; one sample points at yaw 0. Vertically the same with v_samples,
    v_min_angle, v_max_angle (pitch), vertical loop outside, horizontal inside. The direction is
    X rotated by Euler(0, -pitch, yaw): (cos p cos y, cos p sin y, sin p).
  * Each ray starts at <range><min> along its direction and is <range><max> - <range><min>
    long (start = axis * minRange + offset). Objects closer than range_min are therefore not
    seen at all: the ray starts beyond them and reports what lies behind (gazebo-classic issue
    #1564 "Ray sensor looking through walls"). `scan()` gets the same hits by casting from the
    sensor origin with RayCaster's min_range = range_min (ODE reports the first surface
    crossing after a ray's start, also from inside a shape).
  * Raw range of a ray (MultiRayShape::GetRange): range_min + the ray's length, the length
    being the hit depth if ODE reported a contact with depth < the full length
    (ODEMultiRayShape::UpdateCallback), else the full length: no hit gives range_max.
    The ray's retro (intensity) is the hit collision's <laser_retro>, 0 when nothing is hit
    (MultiRayShape::Update resets it to 0; UpdateCallback sets hitCollision->GetLaserRetro()).

Ranges (RaySensor::UpdateImpl)
  * Published count: RangeCount = samples * <horizontal><resolution> (int), vertically
    v_samples * <vertical><resolution>. When it differs from the ray count, each range is
    bilinearly interpolated from the 4 surrounding rays (position j * (rays - 1) /
    (ranges - 1)) and the intensity is the plain mean of those 4 rays' retro.
  * Then, per range, REP 117 masking (gazebo-classic issue #124, fixed by pull request #1567):
      range >= range_max  -> +inf   (this is what "nothing hit" becomes)
      range <= range_min  -> -inf
      otherwise, if the sensor has <noise>: range = noise(range), then clamped to
      [range_min, range_max]. Noise is therefore never applied to the +-inf readings, and a
      noisy reading never leaves [min, max] (it may equal them).
  * <range><resolution> is read by RaySensor::RangeResolution() only; Gazebo does not
    quantise ranges with it. We do the same by default; LaserModel(quantize=True) rounds
    finite ranges to multiples of it (after noise, before the clamp) for those who want it.

Parameters (Sensor.params as ode_sim.description.sdf fills them, or a dict; SDF defaults when
missing):
  samples resolution min_angle max_angle, v_samples v_resolution v_min_angle v_max_angle,
  range_min range_max range_resolution, noise_type noise_mean noise_stddev noise_bias_mean
  noise_bias_stddev noise_precision. Bad values raise ModelError naming the sensor.

Noise (GaussianNoiseModel, created by NoiseFactory from <ray><noise>)
  * type "gaussian" (and the deprecated "gaussian_quantized"): output = in + bias + N(mean,
    stddev) drawn independently per range; bias is drawn once when the sensor loads as
    N(bias_mean, bias_stddev) with a random sign (p = 0.5 negative); bias_mean/bias_stddev
    default 0. If <precision> > 0 the output is rounded to a multiple of it. type "none": no
    noise. A <noise> with no type is treated as gaussian here (params without noise_type but
    with noise_mean/noise_stddev).

gazebo_ros_laser (gazebo_plugins/src/gazebo_ros_laser.cpp, noetic-devel)
  * angle_min / angle_max: the horizontal min_angle / max_angle; angle_increment: the scan's
    angle_step = (max_angle - min_angle) / (RangeCount - 1) (RaySensor::AngleResolution);
    time_increment = 0, scan_time = 0 ("instantaneous simulator scan"); range_min /
    range_max from <range>; ranges and intensities copied (float32 in the message), stamp =
    the measurement's sim time; header.frame_id = the plugin's frameName.
  * With a single range Gazebo divides 0 by 0 (NaN); we publish angle_increment 0 instead.
"""
import math

import numpy as np

from ode_sim.description.model import ModelError

_DEFAULTS = {
    'samples': 640, 'resolution': 1.0, 'min_angle': 0.0, 'max_angle': 0.0,
    'v_samples': 1, 'v_resolution': 1.0, 'v_min_angle': 0.0, 'v_max_angle': 0.0,
    'range_min': 0.0, 'range_max': 0.0, 'range_resolution': 0.0,
    'noise_mean': 0.0, 'noise_stddev': 0.0, 'noise_bias_mean': 0.0,
    'noise_bias_stddev': 0.0, 'noise_precision': 0.0,
}


def _params_and_name(sensor_params):
    """Accept a Sensor (model.Sensor: uses .params, names errors after it) or a plain dict."""
    if hasattr(sensor_params, 'params'):
        name = 'sensor %r' % getattr(sensor_params, 'name', '?')
        return dict(sensor_params.params or {}), name
    return dict(sensor_params or {}), 'ray sensor'


def _get(params, key, conv, where):
    val = params.get(key)
    if val is None or (isinstance(val, str) and not val.strip()):
        return conv(_DEFAULTS[key])
    try:
        num = float(val)
    except (TypeError, ValueError):
        raise ModelError('%s: <%s> must be a number, got %r' % (where, key, val))
    if not math.isfinite(num):
        raise ModelError('%s: <%s> must be finite, got %r' % (where, key, val))
    if conv is int:
        if num != int(num):
            raise ModelError('%s: <%s> must be a whole number, got %r' % (where, key, val))
        return int(num)
    return num


def _angles(count, lo, hi):
    if count == 1:
        return np.zeros(1)
    return lo + np.arange(count) * ((hi - lo) / (count - 1))


def scan_geometry(sensor_params):
    """Parsed and checked scan parameters plus the ray directions (sensor frame)."""
    params, where = _params_and_name(sensor_params)
    g = {}
    for key in ('samples', 'v_samples'):
        g[key] = _get(params, key, int, where)
        if g[key] < 1:
            raise ModelError('%s: <%s> must be at least 1, got %d' % (where, key, g[key]))
    for key in ('resolution', 'v_resolution', 'min_angle', 'max_angle', 'v_min_angle',
                'v_max_angle', 'range_min', 'range_max', 'range_resolution'):
        g[key] = _get(params, key, float, where)
    if g['max_angle'] < g['min_angle']:
        raise ModelError('%s: <max_angle> %g is below <min_angle> %g'
                         % (where, g['max_angle'], g['min_angle']))
    if g['range_min'] < 0:
        raise ModelError('%s: <range><min> must not be negative, got %g' % (where, g['range_min']))
    if not g['range_max'] > g['range_min']:
        raise ModelError('%s: <range><max> (%g) must be greater than <range><min> (%g)'
                         % (where, g['range_max'], g['range_min']))
    if g['range_resolution'] < 0:
        raise ModelError('%s: <range><resolution> must not be negative, got %g'
                         % (where, g['range_resolution']))
    g['range_count'] = int(g['samples'] * g['resolution'])
    g['v_range_count'] = int(g['v_samples'] * g['v_resolution'])
    for key, res in (('range_count', 'resolution'), ('v_range_count', 'v_resolution')):
        if g[key] < 1:
            raise ModelError('%s: samples x <%s> gives %d ranges; it must give at least 1'
                             % (where, res, g[key]))
    yaw = _angles(g['samples'], g['min_angle'], g['max_angle'])
    pitch = _angles(g['v_samples'], g['v_min_angle'], g['v_max_angle'])
    p = np.repeat(pitch, len(yaw))
    y = np.tile(yaw, len(pitch))
    g['directions'] = np.stack([np.cos(p) * np.cos(y), np.cos(p) * np.sin(y), np.sin(p)],
                               axis=1)
    g['params'] = params
    g['where'] = where
    return g


def scan_directions(sensor_params):
    """Unit ray directions (samples * v_samples, 3) in the sensor frame, Gazebo's order."""
    return scan_geometry(sensor_params)['directions']


def _interp_index(count_out, count_in):
    """For each output index: lower and upper input index and the weight of the upper one
    (RaySensor::UpdateImpl's interpolation)."""
    if count_out == 1:
        x = np.zeros(1)
    else:
        x = np.arange(count_out) * (count_in - 1) / (count_out - 1)
    a = np.floor(x).astype(np.int64)
    b = np.minimum(a + 1, count_in - 1)
    return a, b, x - a


class LaserModel:
    """A ray sensor: its directions and what Gazebo + gazebo_ros_laser make of raw hits."""

    def __init__(self, sensor_params, rng=None, quantize=False):
        g = scan_geometry(sensor_params)
        self.where = g['where']
        self.samples = g['samples']
        self.v_samples = g['v_samples']
        self.resolution = g['resolution']
        self.v_resolution = g['v_resolution']
        self.min_angle = g['min_angle']
        self.max_angle = g['max_angle']
        self.v_min_angle = g['v_min_angle']
        self.v_max_angle = g['v_max_angle']
        self.range_min = g['range_min']
        self.range_max = g['range_max']
        self.range_resolution = g['range_resolution']
        self.range_count = g['range_count']
        self.v_range_count = g['v_range_count']
        self.directions = g['directions']
        self.ray_count = len(self.directions)
        self.quantize = bool(quantize)
        self.rng = rng if rng is not None else np.random.default_rng()
        self._noise_setup(g['params'])

    # -- noise -----------------------------------------------------------------------------
    def _noise_setup(self, params):
        ntype = params.get('noise_type')
        ntype = (str(ntype).strip().lower() if ntype is not None else None)
        keys = ('noise_mean', 'noise_stddev', 'noise_bias_mean', 'noise_bias_stddev',
                'noise_precision')
        if ntype is None:
            active = any(params.get(k) not in (None, '') for k in keys)
        elif ntype in ('', 'none'):
            active = False
        elif ntype in ('gaussian', 'gaussian_quantized'):
            active = True
        else:
            raise ModelError('%s: <noise><type> %r is not supported for a ray sensor '
                             '(gaussian or none)' % (self.where, params.get('noise_type')))
        self.noise = active
        self.noise_mean = _get(params, 'noise_mean', float, self.where)
        self.noise_stddev = _get(params, 'noise_stddev', float, self.where)
        self.noise_precision = _get(params, 'noise_precision', float, self.where)
        for key, val in (('stddev', self.noise_stddev), ('precision', self.noise_precision)):
            if val < 0:
                raise ModelError('%s: <noise><%s> must not be negative, got %g'
                                 % (self.where, key, val))
        bias_mean = _get(params, 'noise_bias_mean', float, self.where)
        bias_std = _get(params, 'noise_bias_stddev', float, self.where)
        if not any((self.noise_mean, self.noise_stddev, self.noise_precision, bias_mean,
                    bias_std)):
            active = self.noise = False     # a zero <noise> changes nothing: skip the draws
        self.noise_bias = 0.0
        if active and (bias_mean != 0.0 or bias_std != 0.0):
            bias = self.rng.normal(bias_mean, bias_std) if bias_std > 0 else bias_mean
            self.noise_bias = -bias if self.rng.uniform() < 0.5 else bias

    # -- angles for the message ------------------------------------------------------------
    @property
    def angle_increment(self):
        if self.range_count < 2:
            return 0.0
        return (self.max_angle - self.min_angle) / (self.range_count - 1)

    # -- casting ---------------------------------------------------------------------------
    def scan(self, caster, sensor_pose, exclude=None):
        """Cast the rays with `caster` (an engine.raycast.RayCaster) from the sensor's world
        pose (a transforms.Pose) the way Gazebo does (starting at range_min) and return
        (ranges, intensities) as published."""
        dirs = sensor_pose.rotate(self.directions)
        # one origin, surfaces before range_min ignored: the same hits as rays starting at
        # range_min (ODE reports the first surface crossing after a ray's start)
        dist, who = caster.cast_hits(sensor_pose.p, dirs, self.range_max, exclude,
                                     min_range=self.range_min)
        retro = np.zeros(len(dist))
        hit = who >= 0
        if hit.any():
            retro[hit] = caster.laser_retro()[who[hit]]
        return self.to_ranges(dist, retro)

    def to_ranges(self, distances, retro=None):
        """Raw hit distances from the sensor origin, one per ray in `directions` order
        (inf or NaN: no hit), and optionally each ray's retro -> (ranges, intensities) as
        gazebo_ros_laser publishes them (float64 arrays of range_count * v_range_count)."""
        d = np.asarray(distances, dtype=float).reshape(-1)
        if len(d) != self.ray_count:
            raise ValueError('%s: %d distances for %d rays' % (self.where, len(d), self.ray_count))
        hit = np.isfinite(d) & (d < self.range_max)
        raw = np.where(hit, d, self.range_max)
        if retro is None:
            ret = np.zeros(len(d))
        else:
            ret = np.where(hit, np.asarray(retro, dtype=float).reshape(-1), 0.0)
        raw = raw.reshape(self.v_samples, self.samples)
        ret = ret.reshape(self.v_samples, self.samples)
        if self.range_count != self.samples or self.v_range_count != self.v_samples:
            raw, ret = self._interpolate(raw, ret)
        ranges = raw.reshape(-1).copy()
        intensities = ret.reshape(-1).copy()
        far = ranges >= self.range_max
        near = ~far & (ranges <= self.range_min)
        mid = ~far & ~near
        if self.noise and mid.any():
            val = ranges[mid] + self.noise_bias + self.rng.normal(
                self.noise_mean, self.noise_stddev, size=int(mid.sum()))
            if self.noise_precision > 0:
                val = np.round(val / self.noise_precision) * self.noise_precision
            ranges[mid] = val
        if self.quantize and self.range_resolution > 0:
            ranges[mid] = np.round(ranges[mid] / self.range_resolution) * self.range_resolution
        if self.noise or self.quantize:
            ranges[mid] = np.clip(ranges[mid], self.range_min, self.range_max)
        ranges[far] = np.inf
        ranges[near] = -np.inf
        return ranges, intensities

    def _interpolate(self, raw, ret):
        va, vb, vw = _interp_index(self.v_range_count, self.v_samples)
        ha, hb, hw = _interp_index(self.range_count, self.samples)
        vw = vw[:, None]
        hw = hw[None, :]
        r1 = raw[np.ix_(va, ha)]
        r2 = raw[np.ix_(va, hb)]
        r3 = raw[np.ix_(vb, ha)]
        r4 = raw[np.ix_(vb, hb)]
        rng = (1 - vw) * ((1 - hw) * r1 + hw * r2) + vw * ((1 - hw) * r3 + hw * r4)
        inten = 0.25 * (ret[np.ix_(va, ha)] + ret[np.ix_(va, hb)] + ret[np.ix_(vb, ha)]
                        + ret[np.ix_(vb, hb)])
        return rng, inten
