"""rosbridge_websocket: parameters, ROS wiring and the tornado loop."""
import signal
import socket
import sys
import threading
import time

import rospy
from std_msgs.msg import Int32
from tornado import netutil
from tornado.httpserver import HTTPServer
from tornado.ioloop import IOLoop
from tornado.web import Application

from rosbridge_library.internal.ros_backend import RosBackend
from rosbridge_library.internal.tcpros_backlog import deepen_tcpros_backlog
from rosbridge_server import settings as settings_mod
from rosbridge_server.limits import Counters
from rosbridge_server.websocket_handler import RosbridgeWebSocket, Server


def _clients_publishers():
    from rosbridge_msgs.msg import ConnectedClient, ConnectedClients
    count_pub = rospy.Publisher('client_count', Int32, queue_size=10, latch=True)
    clients_pub = rospy.Publisher('connected_clients', ConnectedClients, queue_size=10,
                                  latch=True)

    def publish(clients):
        count_pub.publish(Int32(len(clients)))
        clients_pub.publish(ConnectedClients([ConnectedClient(ip, rospy.Time.from_sec(t))
                                              for ip, t in clients]))
    publish([])
    return publish


def _authenticator():
    """The original's check: rosauth's `authenticate` service judges the auth message."""
    from rosauth.srv import Authentication

    def check(msg):
        fields = {}
        for name in ('mac', 'client', 'dest', 'rand', 'level'):
            if not isinstance(msg.get(name), str):
                raise ValueError('auth: field %s must be a string' % name)
            fields[name] = msg[name]
        for name in ('t', 'end'):
            if isinstance(msg.get(name), bool) or not isinstance(msg.get(name), (int, float)):
                raise ValueError('auth: field %s must be a number (seconds)' % name)
            fields[name] = rospy.Time.from_sec(max(0.0, float(msg[name])))
        try:
            rospy.wait_for_service('authenticate', timeout=5.0)
        except rospy.ROSException:
            raise RuntimeError('no authenticate service (start rosauth\'s '
                               'ros_mac_authentication)')
        return rospy.ServiceProxy('authenticate', Authentication)(**fields).authenticated
    return check


def _counters_publisher():
    """~limits (diagnostic_msgs/DiagnosticStatus, latched): how often each limit was hit,
    published at most once a second."""
    from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
    pub = rospy.Publisher('~limits', DiagnosticStatus, queue_size=1, latch=True)
    lock = threading.Lock()
    state = {'last': 0.0, 'timer': None, 'values': None}

    def publish():
        with lock:
            values, state['timer'] = state['values'], None
            state['last'] = time.monotonic()
        level = DiagnosticStatus.WARN if any(values.values()) else DiagnosticStatus.OK
        pub.publish(DiagnosticStatus(level=level, name='rosbridge_websocket limits',
                                     message='limits hit since start',
                                     values=[KeyValue(k, str(v))
                                             for k, v in sorted(values.items())]))

    def on_change(values):
        with lock:
            state['values'] = values
            if state['timer'] is not None:
                return
            wait = max(0.0, 1.0 - (time.monotonic() - state['last']))
            state['timer'] = threading.Timer(wait, publish)
            state['timer'].daemon = True
            state['timer'].start()
    return on_change


def _bind(s, stopping):
    """Bind the listening sockets, retrying every retry_startup_delay s as the original."""
    while not rospy.is_shutdown() and not stopping.is_set():
        try:
            return netutil.bind_sockets(s['port'], s['address'] or None,
                                        family=socket.AF_UNSPEC)
        except OSError as e:
            rospy.logwarn('Unable to start server: %s Retrying in %ss.'
                          % (e, s['retry_startup_delay']))
            stopping.wait(s['retry_startup_delay'] or 1.0)
    return None


def main(argv=None):
    stopping = threading.Event()
    loop_box = []

    def stop(*_):
        """SIGINT/SIGTERM (roslaunch's shutdown), also while still starting up."""
        stopping.set()
        if loop_box:
            loop_box[0].add_callback_from_signal(loop_box[0].stop)
    signal.signal(signal.SIGINT, stop)
    signal.signal(signal.SIGTERM, stop)
    rospy.init_node('rosbridge_websocket', disable_signals=True)
    try:
        s = settings_mod.read(lambda name, default: rospy.get_param('~' + name, default))
    except settings_mod.SettingsError as e:
        rospy.logfatal('rosbridge_websocket: %s' % e)
        sys.exit(1)
    if s['bson_only_mode']:
        rospy.logwarn('~bson_only_mode is not supported by this rosbridge_server: JSON/CBOR '
                      'are used')

    backend = RosBackend(unregister_timeout=s['unregister_timeout'])
    counters = Counters(_counters_publisher())
    counters.on_change(counters.snapshot())
    server = Server(backend, s, settings_mod.protocol_settings(s), _clients_publishers(),
                    authenticator=_authenticator() if s['authenticate'] else None,
                    counters=counters)
    if not deepen_tcpros_backlog():    # (the publishers above started rospy's TCPROS server)
        rospy.logwarn('rosbridge_websocket: could not raise the TCPROS listen backlog')
    app_settings = {'websocket_max_message_size': settings_mod.tornado_frame_limit(s)}
    if s['websocket_ping_interval'] > 0:
        app_settings['websocket_ping_interval'] = s['websocket_ping_interval']
        app_settings['websocket_ping_timeout'] = s['websocket_ping_timeout']
    app = Application([(r'/', RosbridgeWebSocket, {'server': server}),
                       (r'/websocket', RosbridgeWebSocket, {'server': server})],
                      **app_settings)
    ssl_options = None
    if s['certfile'] and s['keyfile']:
        ssl_options = {'certfile': s['certfile'], 'keyfile': s['keyfile']}

    sockets = _bind(s, stopping)
    if sockets is None:
        return
    http = HTTPServer(app, ssl_options=ssl_options,
                      max_buffer_size=settings_mod.tornado_frame_limit(s) + 1024 * 1024)
    http.add_sockets(sockets)
    port = sockets[0].getsockname()[1]
    rospy.set_param('~actual_port', port)
    loop = IOLoop.current()
    server.loop = loop
    loop_box.append(loop)
    if stopping.is_set():
        http.stop()
        rospy.signal_shutdown('rosbridge_websocket stopped')
        return
    rospy.on_shutdown(lambda: loop.add_callback(loop.stop))
    scheme = 'wss' if ssl_options else 'ws'
    rospy.loginfo('Rosbridge WebSocket server started at %s://%s:%d%s'
                  % (scheme, s['address'] or '0.0.0.0', port,
                     ' (clients must authenticate: rosauth)' if s['authenticate'] else ''))
    try:
        loop.start()
    finally:
        http.stop()
        rospy.signal_shutdown('rosbridge_websocket stopped')
