"""Reading and validating ekf_localization_node's parameters; `get` is rospy.get_param-like so
this module needs no ROS (the node passes rospy.get_param, tests pass a dict lookup)."""
import numpy as np

from .ekf import DEFAULT_PROCESS_NOISE, DEFAULT_INITIAL_COVARIANCE, STATE_SIZE
from .sensors import SensorConfig

SENSOR_KINDS = (('odom', 'nav_msgs/Odometry'), ('pose', 'geometry_msgs/PoseWithCovarianceStamped'),
                ('twist', 'geometry_msgs/TwistWithCovarianceStamped'), ('imu', 'sensor_msgs/Imu'))
INVALID_FRAMES = ('Invalid frame configuration! The values for map_frame, odom_frame, and '
                  'base_link_frame must be unique. If using a base_link_frame_output values, it '
                  'must not match the map_frame or odom_frame.')
INF = float('inf')


class ParamError(Exception):
    """A fatal configuration problem (logged with ROS_FATAL by the node)."""


class Config:
    pass


def _matrix(get, name, default, log):
    raw = get('~' + name, None)
    if raw is None:
        return default.copy()
    try:
        m = np.asarray([float(v) for v in raw], float)
    except (TypeError, ValueError):
        log('error', 'Parameter %s must be a list of %d numbers; using the default.'
            % (name, STATE_SIZE * STATE_SIZE))
        return default.copy()
    if m.size != STATE_SIZE * STATE_SIZE:
        log('error', 'Parameter %s has %d entries, expected %d (15x15, row-major); using the default.'
            % (name, m.size, STATE_SIZE * STATE_SIZE))
        return default.copy()
    m = m.reshape(STATE_SIZE, STATE_SIZE)
    return m


def read(get, log):
    """-> Config. log(level, text) with level in debug/info/warn/error/fatal."""
    c = Config()
    c.frequency = float(get('~frequency', 30.0))
    if c.frequency <= 0.0:
        log('error', 'Parameter frequency must be > 0 (got %g); using 30.0.' % c.frequency)
        c.frequency = 30.0
    c.sensor_timeout = float(get('~sensor_timeout', 1.0 / c.frequency))
    c.two_d_mode = bool(get('~two_d_mode', False))
    c.map_frame = get('~map_frame', 'map')
    c.odom_frame = get('~odom_frame', 'odom')
    c.base_link_frame = get('~base_link_frame', 'base_link')
    c.base_link_frame_output = get('~base_link_frame_output', c.base_link_frame)
    c.world_frame = get('~world_frame', c.odom_frame)
    if len({c.map_frame, c.odom_frame, c.base_link_frame}) < 3 or \
            c.base_link_frame_output in (c.map_frame, c.odom_frame):
        log('fatal', INVALID_FRAMES)
    if c.world_frame not in (c.map_frame, c.odom_frame):
        log('warn', 'world_frame (%s) should be set to the value of map_frame (%s) or odom_frame '
            '(%s); treating it as odom_frame.' % (c.world_frame, c.map_frame, c.odom_frame))
    c.publish_tf = bool(get('~publish_tf', True))
    c.invert_tf = bool(get('~invert_tf', False))
    c.transform_time_offset = float(get('~transform_time_offset', 0.0))
    c.transform_timeout = float(get('~transform_timeout', 0.0))
    c.publish_acceleration = bool(get('~publish_acceleration', False))
    c.reset_on_time_jump = bool(get('~reset_on_time_jump', False))
    c.predict_to_current_time = bool(get('~predict_to_current_time', False))
    c.disabled_at_startup = bool(get('~disabled_at_startup', False))
    c.gravitational_acceleration = float(get('~gravitational_acceleration', 9.80665))
    c.process_noise_covariance = _matrix(get, 'process_noise_covariance', DEFAULT_PROCESS_NOISE, log)
    c.initial_estimate_covariance = _matrix(get, 'initial_estimate_covariance',
                                            DEFAULT_INITIAL_COVARIANCE, log)
    init = get('~initial_state', None)
    c.initial_state = None
    if init is not None:
        if not isinstance(init, (list, tuple)) or len(init) != STATE_SIZE:
            log('error', 'Initial state must be of size 15. No initial state will be applied.')
        else:
            c.initial_state = np.asarray([float(v) for v in init])
    c.sensors = read_sensors(get, log)
    return c


def read_sensors(get, log):
    sensors = []
    for kind, type_name in SENSOR_KINDS:
        i = 0
        while True:
            name = '%s%d' % (kind, i)
            topic = get('~' + name, None)
            if topic is None:
                break
            cfg_raw = get('~%s_config' % name, None)
            if not isinstance(cfg_raw, (list, tuple)):
                raise ParamError('Could not read sensor update configuration for topic %s (type: %s, '
                                 'expected 15-element boolean array). Parameter %s_config is %s.'
                                 % (topic, type_name, name, 'missing' if cfg_raw is None else
                                    'not a list'))
            config = [bool(v) for v in cfg_raw]
            if len(config) != 15:
                log('warn', 'Configuration vector for %s_config should have 15 entries.' % name)
                config = (config + [False] * 15)[:15]
            differential = bool(get('~%s_differential' % name, False))
            relative = bool(get('~%s_relative' % name, False))
            if differential and relative:
                log('warn', 'Both %s_differential and %s_relative were set to true. Using '
                    'differential mode.' % (name, name))
            kw = {}
            if kind in ('odom', 'imu'):
                kw['pose_rejection_threshold'] = float(get('~%s_pose_rejection_threshold' % name, INF))
                kw['twist_rejection_threshold'] = float(get('~%s_twist_rejection_threshold' % name, INF))
            else:
                th = float(get('~%s_rejection_threshold' % name, INF))
                kw['pose_rejection_threshold'] = kw['twist_rejection_threshold'] = th
            if kind == 'imu':
                kw['linear_acceleration_rejection_threshold'] = float(
                    get('~%s_linear_acceleration_rejection_threshold' % name, INF))
                kw['remove_gravitational_acceleration'] = bool(
                    get('~%s_remove_gravitational_acceleration' % name, False))
            queue = int(get('~%s_queue_size' % name, 1))
            sensors.append(SensorConfig(name, kind, topic, config, max(1, queue),
                                        differential if kind != 'twist' else False,
                                        relative if kind != 'twist' else False, **kw))
            i += 1
    return sensors


def unmeasured_errors(sensors, two_d):
    """The original's 'Neither <var> nor its velocity is being measured' check."""
    names = ('x', 'y', 'z', 'roll', 'pitch', 'yaw')
    out = []
    for i, n in enumerate(names):
        if two_d and i in (2, 3, 4):
            continue
        if not any(s.config[i] or s.config[i + 6] for s in sensors):
            out.append('Neither %s nor its velocity is being measured. This will result in unbounded '
                       'error growth and erratic filter behavior.' % n)
    return out
