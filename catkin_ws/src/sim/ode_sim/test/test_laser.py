"""Gazebo ray sensor + gazebo_ros_laser rules: LaserModel, scan(), fill_laserscan()."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from ode_sim.engine.laser import LaserModel, scan_directions
from ode_sim.ros.convert import fill_laserscan
from ode_sim.description.model import Geometry, ModelError, Sensor
from ode_sim.engine.raycast import RayCaster
from ode_sim.engine.scene import ShapeInstance
from ode_sim.description.transforms import Pose

FOUR = {'samples': 4, 'min_angle': 0.0, 'max_angle': 1.5 * math.pi,
        'range_min': 0.12, 'range_max': 3.5}


def box(key, size, xyz, rpy=(0, 0, 0), retro=0.0, model=None, link='link'):
    return ShapeInstance(key=key, model=model or key, link=link,
                         geometry=Geometry('box', size=tuple(size)),
                         static_pose=Pose.from_xyz_rpy(xyz, rpy), laser_retro=retro)


def room():
    """Walls 1.0, 2.0, 3.0, 1.5 m away along +X, +Y, -X, -Y of the origin."""
    return RayCaster([box('e', (0.2, 10, 2), (1.1, 0, 0), retro=200.0),
                      box('n', (10, 0.2, 2), (0, 2.1, 0)),
                      box('w', (0.2, 10, 2), (-3.1, 0, 0), retro=50.0),
                      box('s', (10, 0.2, 2), (0, -1.6, 0))])


def test_walls_in_four_directions_exact():
    laser = LaserModel(FOUR)
    ranges, intensities = laser.scan(room(), Pose())
    np.testing.assert_allclose(ranges, [1.0, 2.0, 3.0, 1.5], atol=1e-6)
    np.testing.assert_array_equal(intensities, [200.0, 0.0, 50.0, 0.0])


def test_rotated_and_raised_sensor():
    laser = LaserModel(FOUR)
    # turned 90 degrees left: the first ray looks along +Y
    ranges, _ = laser.scan(room(), Pose.from_xyz_rpy((0, 0, 0.5), (0, 0, math.pi / 2)))
    np.testing.assert_allclose(ranges, [2.0, 3.0, 1.5, 1.0], atol=1e-6)
    # moved and pitched down 30 degrees over a floor: the forward ray meets the floor at
    # 0.5 / sin 30 = 1.0 m; the sideways rays stay level and hit the walls; the backward one
    # looks up and passes over the 1 m high west wall
    rc = RayCaster([box('floor', (20, 20, 0.1), (0, 0, -0.05))] + room().shapes)
    ranges, _ = laser.scan(rc, Pose.from_xyz_rpy((-0.5, 0, 0.5), (0, math.pi / 6, 0)))
    np.testing.assert_allclose(ranges[:2], [1.0, 2.0], atol=1e-6)
    assert np.isposinf(ranges[2]) and ranges[3] == pytest.approx(1.5, abs=1e-6)


def test_nothing_within_range_is_plus_inf_with_zero_intensity():
    laser = LaserModel(dict(FOUR, range_max=1.2))
    ranges, intensities = laser.scan(room(), Pose())
    assert ranges[0] == pytest.approx(1.0)
    assert np.all(np.isposinf(ranges[1:]))
    np.testing.assert_array_equal(intensities, [200.0, 0, 0, 0])
    # raw distances: inf, NaN and anything at or beyond range_max are "no hit"
    r, i = LaserModel(FOUR).to_ranges([np.inf, np.nan, 3.5, 7.0], [5, 5, 5, 5])
    assert np.all(np.isposinf(r)) and np.all(i == 0)


def test_min_range_objects_nearer_are_not_seen_and_insides_report_the_exit():
    laser = LaserModel(dict(FOUR, range_min=0.3))
    post = box('post', (0.05, 0.05, 1), (0.2, 0, 0))           # wholly within range_min
    ranges, _ = laser.scan(RayCaster([post] + room().shapes), Pose())
    assert ranges[0] == pytest.approx(1.0)                       # sees the wall behind
    # the sensor sits inside a box reaching 0.5 m ahead: the ray starts inside, exits at 0.5
    housing = box('housing', (1.0, 0.2, 0.2), (0, 0, 0))
    ranges, _ = laser.scan(RayCaster([housing] + room().shapes), Pose())
    np.testing.assert_allclose(ranges, [0.5, 2.0, 0.5, 1.5], atol=1e-9)
    # excluding the sensor's own link removes it
    own = box('housing', (1.0, 0.2, 0.2), (0, 0, 0), model='bot', link='base_scan')
    ranges, _ = laser.scan(RayCaster([own] + room().shapes), Pose(),
                           exclude={('bot', 'base_scan')})
    np.testing.assert_allclose(ranges, [1.0, 2.0, 3.0, 1.5], atol=1e-9)
    # a raw range at or below range_min is -inf (REP 117), never noised
    r, _ = LaserModel(dict(FOUR, range_min=0.3, noise_stddev=0.1)).to_ranges(
        [0.3, 0.1, 1.0, np.inf])
    assert np.isneginf(r[0]) and np.isneginf(r[1]) and np.isfinite(r[2]) and np.isposinf(r[3])


def test_range_resolution_is_not_applied_unless_asked():
    params = dict(FOUR, range_resolution=0.05)
    raw = [1.0123, 2.0, 3.0276, 1.5]
    r, _ = LaserModel(params).to_ranges(raw)
    np.testing.assert_array_equal(r, raw)                        # Gazebo does not quantise
    r, _ = LaserModel(params, quantize=True).to_ranges(raw)
    np.testing.assert_allclose(r, [1.0, 2.0, 3.05, 1.5], atol=1e-12)


def test_noise_precision_rounds():
    laser = LaserModel(dict(FOUR, noise_stddev=0.02, noise_precision=0.01),
                       rng=np.random.default_rng(2))
    r, _ = laser.to_ranges([1.0, 2.0, 3.0, 1.5])
    np.testing.assert_allclose(r * 100, np.round(r * 100), atol=1e-9)


def test_gaussian_noise_statistics_and_clamp():
    n = 20000
    params = {'samples': n, 'min_angle': -1.0, 'max_angle': 1.0, 'range_min': 0.1,
              'range_max': 10.0, 'noise_type': 'gaussian', 'noise_mean': 0.02,
              'noise_stddev': 0.05}
    laser = LaserModel(params, rng=np.random.default_rng(42))
    raw = np.full(n, 2.0)
    raw[::10] = np.inf                                           # no hit: stays +inf
    r, _ = laser.to_ranges(raw)
    assert np.all(np.isposinf(r[::10]))
    noisy = np.delete(r, np.s_[::10])
    assert noisy.mean() == pytest.approx(2.02, abs=0.003)
    assert noisy.std() == pytest.approx(0.05, rel=0.03)
    # seeded: repeatable; a new draw every scan
    again = LaserModel(params, rng=np.random.default_rng(42)).to_ranges(raw)[0]
    np.testing.assert_array_equal(r, again)
    assert not np.array_equal(r, laser.to_ranges(raw)[0])
    # clamped into [range_min, range_max]
    wide = LaserModel(dict(params, noise_stddev=3.0), rng=np.random.default_rng(1))
    r, _ = wide.to_ranges(np.full(n, 1.0))
    assert r.min() == 0.1 and r.max() == 10.0
    assert np.all((r >= 0.1) & (r <= 10.0))


def test_noise_bias_is_drawn_once_with_a_random_sign():
    means = []
    for seed in range(6):
        laser = LaserModel(dict(FOUR, range_max=10, noise_bias_mean=0.3),
                           rng=np.random.default_rng(seed))
        assert abs(laser.noise_bias) == pytest.approx(0.3)
        r, _ = laser.to_ranges([2.0, 2.0, 2.0, 2.0])
        np.testing.assert_allclose(r, 2.0 + laser.noise_bias)
        means.append(laser.noise_bias)
    assert min(means) < 0 < max(means)


def test_horizontal_resolution_interpolates_like_gazebo():
    params = {'samples': 3, 'resolution': 2, 'min_angle': -1.0, 'max_angle': 1.0,
              'range_min': 0.1, 'range_max': 5.0}
    laser = LaserModel(params)
    assert laser.ray_count == 3 and laser.range_count == 6
    assert laser.angle_increment == pytest.approx(2.0 / 5)
    r, i = laser.to_ranges([1.0, 2.0, np.inf], [10.0, 20.0, 30.0])
    # positions 0, 0.4, 0.8, 1.2, 1.6, 2.0 between rays; no hit counts as range_max (5)
    np.testing.assert_allclose(r[:5], [1.0, 1.4, 1.8, 2.6, 3.8])
    assert np.isposinf(r[5])
    # intensity: the plain mean of the 4 (here 2 distinct) neighbours, whatever the weights
    # (so even the first range, exactly on ray 0, averages rays 0 and 1); no hit has 0
    np.testing.assert_allclose(i, [15, 15, 15, 10, 10, 0])


def test_vertical_samples_order_and_count():
    params = {'samples': 5, 'min_angle': -0.5, 'max_angle': 0.5, 'v_samples': 3,
              'v_min_angle': -0.2, 'v_max_angle': 0.2, 'range_min': 0.1, 'range_max': 5.0}
    d = scan_directions(params)
    assert d.shape == (15, 3)
    pitch = np.arcsin(d[:, 2])
    yaw = np.arctan2(d[:, 1], d[:, 0])
    np.testing.assert_allclose(pitch, np.repeat([-0.2, 0.0, 0.2], 5), atol=1e-12)
    np.testing.assert_allclose(yaw, np.tile(np.linspace(-0.5, 0.5, 5), 3), atol=1e-12)
    assert LaserModel(params).to_ranges(np.full(15, 1.0))[0].shape == (15,)


def test_fill_laserscan_plain_object_and_message():
    laser = LaserModel({'samples': 360, 'min_angle': 0.0, 'max_angle': 6.28, 'range_min': 0.12,
                        'range_max': 3.5})
    ranges, intensities = laser.to_ranges(np.full(360, 1.25))
    msg = SimpleNamespace(header=SimpleNamespace(stamp=None, frame_id=''))
    out = fill_laserscan(msg, laser, ranges, intensities, stamp=12.5, frame='base_scan')
    assert out is msg and msg.header.stamp == 12.5 and msg.header.frame_id == 'base_scan'
    assert (msg.angle_min, msg.angle_max) == (0.0, 6.28)
    assert msg.angle_increment == pytest.approx(6.28 / 359)
    assert (msg.time_increment, msg.scan_time) == (0.0, 0.0)
    assert (msg.range_min, msg.range_max) == (0.12, 3.5)
    assert len(msg.ranges) == 360 and msg.ranges[0] == 1.25 and len(msg.intensities) == 360
    import sensor_msgs.msg as sensor_msgs   # Debian's python3-sensor-msgs: missing = broken install
    from io import BytesIO
    real = fill_laserscan(None, laser, laser.to_ranges(np.full(360, np.inf))[0],
                          np.zeros(360), frame='laser')
    assert isinstance(real, sensor_msgs.LaserScan)
    buf = BytesIO()
    real.serialize(buf)                                          # float32 fields: +inf survives
    back = sensor_msgs.LaserScan().deserialize(buf.getvalue())
    assert math.isinf(back.ranges[0]) and back.header.frame_id == 'laser'
    one = LaserModel({'samples': 1, 'range_max': 2.0})
    assert one.angle_increment == 0.0 and one.directions.tolist() == [[1.0, 0.0, 0.0]]


@pytest.mark.parametrize('params, message', [
    ({'range_max': 0}, r'<range><max> \(0\) must be greater than <range><min> \(0\)'),
    ({'range_max': 5, 'samples': 0}, '<samples> must be at least 1'),
    ({'range_max': 5, 'samples': 'many'}, "<samples> must be a number, got 'many'"),
    ({'range_max': 5, 'samples': 2.5}, '<samples> must be a whole number'),
    ({'range_max': 5, 'min_angle': 1, 'max_angle': 0}, '<max_angle> 0 is below <min_angle> 1'),
    ({'range_max': 5, 'resolution': 0.1, 'samples': 5}, 'gives 0 ranges'),
    ({'range_max': 5, 'noise_type': 'salt'}, "<noise><type> 'salt' is not supported"),
    ({'range_max': 5, 'noise_stddev': -1}, '<noise><stddev> must not be negative'),
])
def test_bad_parameters_give_one_clear_line(params, message):
    with pytest.raises(ModelError, match=message) as err:
        LaserModel(params)
    assert '\n' not in str(err.value)
    assert str(err.value).startswith('ray sensor: ')


def test_sensor_object_names_itself_in_errors_and_string_values_parse():
    s = Sensor(name='hokuyo', type='ray', link='base_scan',
               params={'samples': '360', 'min_angle': '0', 'max_angle': '6.28',
                       'range_min': '0.12', 'range_max': '3.5', 'noise_mean': '0.0',
                       'noise_stddev': '0.01'})
    laser = LaserModel(s)
    assert laser.ray_count == 360 and laser.noise and laser.noise_stddev == 0.01
    s.params['range_max'] = '0.1'
    with pytest.raises(ModelError, match=r"^sensor 'hokuyo': <range><max>"):
        LaserModel(s)


def test_zero_or_none_noise_leaves_ranges_alone():
    raw = [1.0, 2.0, 3.0, 1.5]
    for extra in ({'noise_mean': 0.0, 'noise_stddev': 0.0}, {'noise_type': 'none',
                                                             'noise_stddev': 0.5}):
        laser = LaserModel(dict(FOUR, **extra))
        assert not laser.noise
        np.testing.assert_array_equal(laser.to_ranges(raw)[0], raw)
    assert LaserModel(dict(FOUR, noise_type='gaussian', noise_stddev=0.1)).noise
