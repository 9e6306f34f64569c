"""The host side of a rosserial link, with no ROS imports: framing, negotiation, time sync,
parameter and log requests, device services, resync and the original's log messages.

Everything ROS (message classes, publishers, subscribers, services, parameters, logging, the
clock) goes through a *backend* object (rosserial_python.ros_backend for rospy, a fake in the
unit tests):

    backend.log(level, text)                 level: 'debug' 'info' 'warn' 'error' 'fatal'
    backend.now() -> (secs, nsecs)           ROS time sent to the device
    backend.get_param(name) -> value         KeyError when it does not exist
    backend.publisher(info) -> obj           obj.handle(payload); obj.message_type
    backend.subscriber(info, deliver) -> obj deliver(payload) sends to the device; obj.unregister()
    backend.service_server(info, call) -> obj    call(request_payload) -> response payload
    backend.service_client(info) -> obj      obj.call(request_payload) -> response payload
    backend.check_md5(info, part)            raises ValueError on a mismatch ('request'/'response')
    backend.diagnostics(message, lastsync, lastsync_lost)

The port is any object with read_some() -> bytes (b'' when nothing arrived within its short
poll timeout), write(data) and flush_input(); errors it raises (OSError, serial errors) end
run() and the caller reconnects.
"""
import threading
import time

from . import protocol as p

LEVELS = {0: 'debug', 1: 'info', 2: 'warn', 3: 'error', 4: 'fatal'}

MSG_MISMATCH = ('Mismatched protocol version in packet (%s): lost sync or rosserial_python is '
                'from different ros release than the rosserial client')
MSG_NEVER_SYNCED = ('Unable to sync with device; possible link problem or link software version '
                    'mismatch such as hydro rosserial_python with groovy Arduino')
MSG_LOST_SYNC = 'Lost sync with device, restarting...'
DIAG_MISMATCH = ('Mismatched protocol version in packet: lost sync or rosserial_python is from '
                 'different ros release than the rosserial client')


class DeviceServiceTimeout(Exception):
    pass


class DeviceService(object):
    """A service served by the device: ROS calls wait for its response frame, with a timeout
    (the original waits forever, hanging the caller when the device is silent)."""

    def __init__(self, name, message_type):
        self.name = name
        self.message_type = message_type
        self.request_id = None
        self.ros = None
        self._call_lock = threading.Lock()
        self._done = threading.Event()
        self._response = None

    def handle_response(self, payload):
        self._response = payload
        self._done.set()

    def call(self, link, payload, timeout):
        with self._call_lock:
            if self.request_id is None:
                raise DeviceServiceTimeout('service %s: the device has not announced its request '
                                           'topic yet' % self.name)
            self._done.clear()
            self._response = None
            link.send(self.request_id, payload)
            if not self._done.wait(timeout):
                raise DeviceServiceTimeout('service %s: no response from the device within %.1f s'
                                           % (self.name, timeout))
            return self._response


class DeviceClient(object):
    """A service the device calls on the ROS network."""

    def __init__(self, name, message_type, ros):
        self.name = name
        self.message_type = message_type
        self.ros = ros
        self.response_id = None


class Stats(object):
    def __init__(self):
        self.frames = 0
        self.bad_checksums = 0
        self.bad_versions = 0
        self.timeouts = 0
        self.unknown_ids = 0
        self.oversize_drops = 0
        self.renegotiations = 0

    def as_dict(self):
        return dict(self.__dict__)


class DeviceLink(object):

    def __init__(self, port, backend, timeout=5.0, flush=True, clock=time.monotonic,
                 service_timeout=None):
        self.port = port
        self.backend = backend
        self.timeout = timeout
        self.service_timeout = timeout if service_timeout is None else service_timeout
        self.flush = flush
        self.clock = clock
        self.parser = p.FrameParser()
        self.stats = Stats()
        self.write_lock = threading.Lock()
        self.lastsync = clock()
        self.lastsync_wall = None       # time.time() of the last sync, for diagnostics
        self.lastsync_lost_wall = None
        self.synced = False
        self.frame_start = None
        self.last_request = None
        self.buffer_out = -1
        self.buffer_in = -1
        self.publishers = {}        # topic name -> backend publisher
        self.subscribers = {}       # topic name -> backend subscriber
        self.sub_ids = {}           # topic name -> device subscriber id
        self.services = {}          # topic name -> DeviceService
        self.clients = {}           # topic name -> DeviceClient
        self.endpoints = {}         # device topic id -> handler(payload)
        self.handlers = {
            p.ID_PUBLISHER: self.setup_publisher,
            p.ID_SUBSCRIBER: self.setup_subscriber,
            p.ID_SERVICE_SERVER + p.ID_PUBLISHER: self.setup_service_server_publisher,
            p.ID_SERVICE_SERVER + p.ID_SUBSCRIBER: self.setup_service_server_subscriber,
            p.ID_SERVICE_CLIENT + p.ID_PUBLISHER: self.setup_service_client_publisher,
            p.ID_SERVICE_CLIENT + p.ID_SUBSCRIBER: self.setup_service_client_subscriber,
            p.ID_PARAMETER_REQUEST: self.handle_parameter_request,
            p.ID_LOG: self.handle_log,
            p.ID_TIME: self.handle_time_request,
        }

    # -- output ------------------------------------------------------------------------------

    def log(self, level, text):
        self.backend.log(level, text)

    def write(self, data):
        with self.write_lock:
            self.port.write(data)

    def send(self, topic_id, payload):
        self.write(p.encode_frame(topic_id, payload))

    def request_topics(self):
        self.log('info', 'Requesting topics...')
        if self.flush:
            self.port.flush_input()
            self.parser.reset()
            self.frame_start = None
        self.last_request = self.clock()
        self.write(p.REQUEST_TOPICS)

    def tx_stop(self):
        self.write(p.TX_STOP)
        self.log('info', 'Send tx stop request')

    def deliver_to_device(self, topic_name, payload):
        """A ROS message for a device subscriber (called from subscriber threads)."""
        topic_id = self.sub_ids.get(topic_name)
        if topic_id is None:
            return
        if self.buffer_in > 0 and len(payload) + 8 > self.buffer_in:
            self.stats.oversize_drops += 1
            self.log('error', 'Message from ROS network dropped: message larger than buffer.\n'
                     '%s: %d bytes, device input buffer %d bytes'
                     % (topic_name, len(payload) + 8, self.buffer_in))
            return
        self.send(topic_id, payload)

    # -- input -------------------------------------------------------------------------------

    def start(self):
        self.lastsync = self.clock()
        self.request_topics()

    def run(self, is_shutdown):
        """Read and dispatch until is_shutdown() is true; port errors propagate."""
        self.start()
        while not is_shutdown():
            self.step()

    def step(self):
        data = self.port.read_some()
        now = self.clock()
        if data:
            for ev in self.parser.feed(data):
                self.handle_event(ev)
        if self.parser.in_frame:
            if self.frame_start is None:
                self.frame_start = now
            elif now - self.frame_start > self.timeout:
                self.read_timeout()
        else:
            self.frame_start = None
        self.check_sync()

    def read_timeout(self):
        step = self.parser.partial_step()
        got = self.parser.reset()
        self.frame_start = None
        self.stats.timeouts += 1
        self.log('warn', 'Serial Port read returned short (expected more than %d bytes, received '
                 '%d instead).' % (got, got))
        self.log('warn', 'Last read step: %s' % step)
        if step == 'data':
            self.log('info', 'Packet Failed :  Failed to read msg data')
            self.diagnostics('Packet Failed : Failed to read msg data')
        self.request_topics()

    def check_sync(self):
        now = self.clock()
        if now - self.lastsync <= 3 * self.timeout:
            return
        self.log('error', MSG_LOST_SYNC if self.synced else MSG_NEVER_SYNCED)
        self.lastsync_lost_wall = time.time()
        self.diagnostics('no sync with device')
        self.stats.renegotiations += 1
        self.request_topics()
        self.lastsync = now

    def diagnostics(self, message):
        try:
            self.backend.diagnostics(message, self.lastsync_wall, self.lastsync_lost_wall)
        except Exception as e:  # diagnostics must never stop the link
            self.log('debug', 'diagnostics not published: %s' % e)

    def handle_event(self, ev):
        if ev.kind == 'frame':
            self.stats.frames += 1
            self.dispatch(ev.topic_id, ev.payload)
        elif ev.kind == 'bad_version':
            self.stats.bad_versions += 1
            self.log('error', MSG_MISMATCH % ('0x%02x' % ev.version))
            self.log('info', 'Protocol version of client is %s, expected Rev 1 (rosserial 0.5+)'
                     % ev.describe())
            self.diagnostics(DIAG_MISMATCH)
        elif ev.kind == 'bad_length_checksum':
            self.stats.bad_checksums += 1
            self.log('info', 'Wrong checksum for msg length, length %d, dropping message.'
                     % ev.length)
        elif ev.kind == 'bad_data_checksum':
            self.stats.bad_checksums += 1
            self.log('info', 'wrong checksum for topic id and msg')

    def dispatch(self, topic_id, payload):
        handler = self.handlers.get(topic_id) or self.endpoints.get(topic_id)
        if handler is None:
            self.stats.unknown_ids += 1
            self.log('error', 'Tried to publish before configured, topic id %d' % topic_id)
            # at most one renegotiation a second while the device keeps sending
            if self.last_request is None or self.clock() - self.last_request > 1.0:
                self.request_topics()
            return
        try:
            handler(payload)
        except Exception as e:
            self.log('error', 'Error handling a message on topic id %d (%d bytes): %s'
                     % (topic_id, len(payload), e))

    # -- negotiation -------------------------------------------------------------------------

    def _topic_info(self, payload):
        return p.TopicInfo.decode(payload)

    def setup_publisher(self, payload):
        if not payload:
            # our client library sends an empty frame on id 0 when it (re)starts: negotiate
            self.request_topics()
            return
        info = self._topic_info(payload)
        try:
            pub = self.publishers.get(info.topic_name)
            if pub is None or pub.message_type != info.message_type:
                pub = self.backend.publisher(info)
                self.publishers[info.topic_name] = pub
            else:
                self.backend.check_md5(info, 'message')
            self.endpoints[info.topic_id] = pub.handle
            self.log('info', 'Setup publisher on %s [%s]' % (info.topic_name, info.message_type))
        except Exception as e:
            self.log('error', 'Creation of publisher failed: %s' % e)
            return
        if self.buffer_out < 0:
            self.buffer_out = info.buffer_size
            self.log('info', 'Note: publish buffer size is %d bytes' % self.buffer_out)

    def setup_subscriber(self, payload):
        info = self._topic_info(payload)
        try:
            sub = self.subscribers.get(info.topic_name)
            if sub is not None and sub.message_type != info.message_type:
                sub.unregister()
                sub = None
            if sub is None:
                name = info.topic_name
                sub = self.backend.subscriber(
                    info, lambda payload, name=name: self.deliver_to_device(name, payload))
                self.subscribers[info.topic_name] = sub
            else:
                self.backend.check_md5(info, 'message')
            self.sub_ids[info.topic_name] = info.topic_id
            self.log('info', 'Setup subscriber on %s [%s]' % (info.topic_name, info.message_type))
        except Exception as e:
            self.log('error', 'Creation of subscriber failed: %s' % e)
            return
        if self.buffer_in < 0:
            self.buffer_in = info.buffer_size
            self.log('info', 'Note: subscribe buffer size is %d bytes' % self.buffer_in)

    def _device_service(self, info):
        srv = self.services.get(info.topic_name)
        if srv is None or srv.message_type != info.message_type:
            srv = DeviceService(info.topic_name, info.message_type)
            srv.ros = self.backend.service_server(
                info, lambda payload, srv=srv: srv.call(self, payload, self.service_timeout))
            self.services[info.topic_name] = srv
        return srv

    def setup_service_server_publisher(self, payload):
        info = self._topic_info(payload)
        try:
            self.backend.check_md5(info, 'response')
            srv = self._device_service(info)
            self.endpoints[info.topic_id] = srv.handle_response
            self.log('info', 'Setup service server on %s [%s]'
                     % (info.topic_name, info.message_type))
        except Exception as e:
            self.log('error', 'Creation of service server failed: %s' % e)

    def setup_service_server_subscriber(self, payload):
        info = self._topic_info(payload)
        try:
            self.backend.check_md5(info, 'request')
            srv = self._device_service(info)
            srv.request_id = info.topic_id
        except Exception as e:
            self.log('error', 'Creation of service server failed: %s' % e)

    def _device_client(self, info):
        cli = self.clients.get(info.topic_name)
        if cli is None or cli.message_type != info.message_type:
            cli = DeviceClient(info.topic_name, info.message_type,
                               self.backend.service_client(info))
            self.clients[info.topic_name] = cli
        return cli

    def setup_service_client_publisher(self, payload):
        info = self._topic_info(payload)
        try:
            self.backend.check_md5(info, 'request')
            cli = self._device_client(info)
            self.endpoints[info.topic_id] = lambda payload, cli=cli: self._call_ros(cli, payload)
            self.log('info', 'Setup service client on %s [%s]'
                     % (info.topic_name, info.message_type))
        except Exception as e:
            self.log('error', 'Creation of service client failed: %s' % e)

    def setup_service_client_subscriber(self, payload):
        info = self._topic_info(payload)
        try:
            self.backend.check_md5(info, 'response')
            self._device_client(info).response_id = info.topic_id
        except Exception as e:
            self.log('error', 'Creation of service client failed: %s' % e)

    def _call_ros(self, cli, payload):
        """The device calls a ROS service: in a thread of its own, the read loop goes on."""
        def work():
            try:
                response = cli.ros.call(payload)
            except Exception as e:
                self.log('error', 'Service %s called by the device failed: %s' % (cli.name, e))
                return
            if cli.response_id is not None:
                self.send(cli.response_id, response)
        threading.Thread(target=work, daemon=True).start()

    # -- system requests ---------------------------------------------------------------------

    def handle_time_request(self, payload):
        secs, nsecs = self.backend.now()
        self.send(p.ID_TIME, p.encode_time(secs, nsecs))
        self.lastsync = self.clock()
        self.lastsync_wall = time.time()
        self.synced = True

    def handle_parameter_request(self, payload):
        name = p.decode_param_request(payload)
        try:
            value = self.backend.get_param(name)
        except KeyError:
            self.log('error', 'Parameter %s does not exist' % name)
            return
        try:
            ints, floats, strings = p.param_to_response(name, value)
        except p.ParamError as e:
            self.log('error', str(e))
            return
        self.send(p.ID_PARAMETER_REQUEST, p.encode_param_response(ints, floats, strings))

    def handle_log(self, payload):
        level, msg = p.decode_log(payload)
        self.log(LEVELS.get(level, 'info'), msg)
