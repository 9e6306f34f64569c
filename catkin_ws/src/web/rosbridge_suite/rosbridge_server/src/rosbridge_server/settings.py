"""rosbridge_websocket's parameters: names and defaults of the original, parsed and checked
(no ROS imports: `read(get_param)` takes rospy.get_param or a dict's get)."""
from rosbridge_library.internal.globs import GlobError as SettingsError, parse_glob  # noqa: F401

DEFAULTS = {
    'port': 9090,
    'address': '',
    'retry_startup_delay': 5.0,
    'fragment_timeout': 600,
    'delay_between_messages': 0.0,
    'max_message_size': None,
    'unregister_timeout': 10.0,
    'use_compression': False,
    'websocket_ping_interval': 0.0,
    'websocket_ping_timeout': 30.0,
    'websocket_external_port': None,
    'topics_glob': '[*]',
    'services_glob': '[*]',
    'params_glob': '[*]',
    'authenticate': False,
    'bson_only_mode': False,
    'certfile': None,
    'keyfile': None,
    # ours: the bounds of each client's outgoing queue
    'max_client_queue_messages': 1000,
    'max_client_queue_bytes': 32 * 1024 * 1024,
    # ours: per-client limits (each hit is a status message / log line and a counter)
    'max_client_subscriptions': 100,
    'max_connections_per_address': 32,
    # incoming, per client address (all its connections): 2 s of it may come at once
    'max_client_bytes_per_second': 4 * 1024 * 1024,
    'max_client_messages_per_second': 1000,
    'max_client_errors_per_second': 10,                 # bad messages; 10 s of it at once
    'auth_timeout': 15.0,                               # authenticate: first op within this
}

INT_LIMITS = ('max_client_subscriptions', 'max_connections_per_address',
              'max_client_bytes_per_second', 'max_client_messages_per_second',
              'max_client_errors_per_second')

# tornado's own limit for one incoming frame is this many times max_message_size: a larger
# frame than max_message_size still arrives and gets a status message; a far larger one
# makes tornado close the connection (1009, "message too big").
FRAME_LIMIT_FACTOR = 4
DEFAULT_MAX_MESSAGE_SIZE = 10 * 1024 * 1024   # tornado's default limit


def _none(value):
    return value is None or (isinstance(value, str) and value.strip() in ('', 'None', 'none'))


def _bool(value, name):
    if isinstance(value, bool):
        return value
    if isinstance(value, str) and value.strip().lower() in ('true', 'false', '1', '0'):
        return value.strip().lower() in ('true', '1')
    if isinstance(value, int):
        return bool(value)
    raise SettingsError('~%s: expected true or false, got %r' % (name, value))


def read(get_param):
    """The effective settings from `get_param(name, default)`."""
    s = {}
    for name, default in DEFAULTS.items():
        s[name] = get_param(name, default)
    for name in ('max_message_size', 'websocket_external_port', 'certfile', 'keyfile'):
        if _none(s[name]):
            s[name] = None
    for name in ('port', 'max_message_size', 'websocket_external_port',
                 'max_client_queue_messages', 'max_client_queue_bytes') + INT_LIMITS:
        if s[name] is None:
            continue
        try:
            s[name] = int(s[name])
        except (TypeError, ValueError):
            raise SettingsError('~%s: expected an integer, got %r' % (name, s[name]))
    for name in ('retry_startup_delay', 'fragment_timeout', 'delay_between_messages',
                 'unregister_timeout', 'websocket_ping_interval', 'websocket_ping_timeout',
                 'auth_timeout'):
        try:
            s[name] = float(s[name])
        except (TypeError, ValueError):
            raise SettingsError('~%s: expected a number, got %r' % (name, s[name]))
        if s[name] < 0:
            raise SettingsError('~%s: must not be negative, got %s' % (name, s[name]))
    if not 0 <= s['port'] <= 65535:
        raise SettingsError('~port: expected 0..65535, got %d' % s['port'])
    for name in ('max_client_queue_messages', 'max_client_queue_bytes') + INT_LIMITS:
        if s[name] < 1:
            raise SettingsError('~%s: must be positive, got %d' % (name, s[name]))
    if s['max_message_size'] is not None and s['max_message_size'] < 1:
        raise SettingsError('~max_message_size: must be positive, got %d'
                            % s['max_message_size'])
    for name in ('topics_glob', 'services_glob', 'params_glob'):
        s[name] = parse_glob(s[name], name)
    s['authenticate'] = _bool(s['authenticate'], 'authenticate')
    if s['address'] in ('0.0.0.0', None):    # all interfaces, IPv6 too (browsers' localhost)
        s['address'] = ''
    return s


def protocol_settings(s):
    """The part of the settings each client's Protocol uses."""
    return {'fragment_timeout': s['fragment_timeout'],
            'delay_between_messages': s['delay_between_messages'],
            'max_message_size': s['max_message_size'] or DEFAULT_MAX_MESSAGE_SIZE,
            'topics_glob': s['topics_glob'],
            'services_glob': s['services_glob'],
            'params_glob': s['params_glob'],
            'max_subscriptions': s['max_client_subscriptions']}


def tornado_frame_limit(s):
    return FRAME_LIMIT_FACTOR * (s['max_message_size'] or DEFAULT_MAX_MESSAGE_SIZE)
