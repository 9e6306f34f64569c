"""The host's link core against a fake device on a real pty (no roscore): negotiation,
publishing, subscribing, time sync, parameters, logging, device services, garbage, timeouts,
lost sync and a vanishing port, with the original's log messages."""
import threading
import time

import pytest

from fake_device import EMPTY_MD5, STRING_MD5, FakeDevice
from rosserial_python import protocol as p
from rosserial_python.link import DeviceLink, DeviceServiceTimeout
from rosserial_python.ports import SerialPort

KNOWN_MD5 = {('std_msgs/String', 'message'): STRING_MD5,
             ('std_msgs/Empty', 'message'): EMPTY_MD5,
             ('rosserial_arduino/Test', 'request'): '0825d95fdfa2c8f4bbb4e9c74bccd3fd',
             ('rosserial_arduino/Test', 'response'): '0825d95fdfa2c8f4bbb4e9c74bccd3fd'}


class FakeBackend(object):
    def __init__(self, params=None):
        self.logs = []
        self.published = []
        self.deliver = {}
        self.services = {}
        self.params = params or {}
        self.diag = []

    def log(self, level, text):
        self.logs.append((level, text))

    def has_log(self, level, text):
        return (level, text) in self.logs

    def now(self):
        return 1234, 5678

    def get_param(self, name):
        return self.params[name]

    def check_md5(self, info, part):
        want = KNOWN_MD5[(info.message_type, part)]
        if want != info.md5sum:
            raise ValueError('Checksum does not match: %s,%s' % (want, info.md5sum))

    def publisher(self, info):
        self.check_md5(info, 'message')
        backend = self

        class Pub(object):
            message_type = info.message_type

            def handle(self, payload):
                backend.published.append((info.topic_name, payload))
        return Pub()

    def subscriber(self, info, deliver):
        self.check_md5(info, 'message')
        self.deliver[info.topic_name] = deliver

        class Sub(object):
            message_type = info.message_type

            def unregister(self):
                pass
        return Sub()

    def service_server(self, info, call):
        self.services[info.topic_name] = call
        return object()

    def service_client(self, info):
        class Cli(object):
            def call(self, payload):
                return p.pack_string(p.Reader(payload).string().upper())
        return Cli()

    def diagnostics(self, message, lastsync, lastsync_lost):
        self.diag.append(message)


def info(topic_id, name, mtype, md5, size=512):
    return p.TopicInfo(topic_id, name, mtype, md5, size)


CHATTER = (p.ID_PUBLISHER, info(125, 'chatter', 'std_msgs/String', STRING_MD5))
TOGGLE = (p.ID_SUBSCRIBER, info(100, 'toggle_led', 'std_msgs/Empty', EMPTY_MD5))


class Bench(object):
    def __init__(self, announce, timeout=5.0, params=None, answer=True):
        self.dev = FakeDevice(announce, answer_topic_requests=answer)
        self.backend = FakeBackend(params)
        self.port = SerialPort(self.dev.path, 57600)
        self.link = DeviceLink(self.port, self.backend, timeout=timeout, service_timeout=0.5)
        self.stop = False
        self.error = None
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self):
        try:
            self.link.run(lambda: self.stop)
        except Exception as e:  # the port vanished
            self.error = e

    def wait_log(self, level, text, timeout=10.0):
        self.dev.wait_for(lambda: self.backend.has_log(level, text), timeout,
                          'log %s %r (have %r)' % (level, text, self.backend.logs[-5:]))

    def close(self):
        self.stop = True
        self.thread.join(5)
        self.port.close()
        self.dev.close()


@pytest.fixture
def bench_factory():
    made = []

    def make(*a, **kw):
        b = Bench(*a, **kw)
        made.append(b)
        return b
    yield make
    for b in made:
        b.close()


def test_negotiation_and_publish(bench_factory):
    b = bench_factory([CHATTER, TOGGLE])
    b.wait_log('info', 'Setup publisher on chatter [std_msgs/String]')
    b.wait_log('info', 'Setup subscriber on toggle_led [std_msgs/Empty]')
    assert b.backend.has_log('info', 'Requesting topics...')
    assert b.backend.has_log('info', 'Note: publish buffer size is 512 bytes')
    assert b.backend.has_log('info', 'Note: subscribe buffer size is 512 bytes')
    # the time request of the handshake was answered with the backend's time
    b.dev.wait_for(lambda: b.dev.frames_on(p.ID_TIME), what='time reply')
    assert p.decode_time(b.dev.frames_on(p.ID_TIME)[0]) == (1234, 5678)
    for i in range(5):
        b.dev.send(125, p.pack_string('hello world! %d' % i))
    b.dev.wait_for(lambda: len(b.backend.published) == 5, what='5 chatter messages')
    assert b.backend.published[4] == ('chatter', p.pack_string('hello world! 4'))


def test_ros_message_to_device_subscriber(bench_factory):
    b = bench_factory([TOGGLE])
    b.dev.wait_for(lambda: 'toggle_led' in b.backend.deliver, what='subscriber setup')
    b.wait_log('info', 'Setup subscriber on toggle_led [std_msgs/Empty]')
    b.backend.deliver['toggle_led'](b'')
    b.dev.wait_for(lambda: b.dev.frames_on(100), what='frame on the subscriber id 100')
    # larger than the device's input buffer: dropped with the original's message
    b.link.buffer_in = 16
    b.backend.deliver['toggle_led'](bytes(20))
    assert b.backend.logs[-1][1].startswith(
        'Message from ROS network dropped: message larger than buffer.')
    assert b.link.stats.oversize_drops == 1


def test_md5_mismatch(bench_factory):
    bad = (p.ID_PUBLISHER, info(125, 'chatter', 'std_msgs/String', 'ffff'))
    b = bench_factory([bad])
    b.wait_log('error', 'Creation of publisher failed: Checksum does not match: %s,ffff'
               % STRING_MD5)
    b.dev.send(125, p.pack_string('x'))
    b.wait_log('error', 'Tried to publish before configured, topic id 125')


def test_parameters_and_logging(bench_factory):
    b = bench_factory([CHATTER], params={'~gains': [1.5, 2.5], 'rate': 10, 'names': ['a', 'b'],
                                         'cfg': {'a': 1}})
    b.wait_log('info', 'Setup publisher on chatter [std_msgs/String]')
    b.dev.send(p.ID_PARAMETER_REQUEST, p.encode_param_request('~gains'))
    b.dev.send(p.ID_PARAMETER_REQUEST, p.encode_param_request('rate'))
    b.dev.send(p.ID_PARAMETER_REQUEST, p.encode_param_request('names'))
    b.dev.wait_for(lambda: len(b.dev.frames_on(p.ID_PARAMETER_REQUEST)) == 3, what='3 replies')
    replies = [p.decode_param_response(x) for x in b.dev.frames_on(p.ID_PARAMETER_REQUEST)]
    assert replies == [([], [1.5, 2.5], []), ([10], [], []), ([], [], ['a', 'b'])]
    b.dev.send(p.ID_PARAMETER_REQUEST, p.encode_param_request('missing'))
    b.wait_log('error', 'Parameter missing does not exist')
    b.dev.send(p.ID_PARAMETER_REQUEST, p.encode_param_request('cfg'))
    b.wait_log('error', 'Cannot send param cfg because it is a dictionary')
    assert len(b.dev.frames_on(p.ID_PARAMETER_REQUEST)) == 3   # no reply to either
    for level, name in enumerate(['debug', 'info', 'warn', 'error', 'fatal']):
        b.dev.send(p.ID_LOG, p.encode_log(level, 'device says %s' % name))
        b.wait_log(name, 'device says %s' % name)


def test_garbage_is_survived_without_losing_messages(bench_factory):
    b = bench_factory([CHATTER])
    b.wait_log('info', 'Setup publisher on chatter [std_msgs/String]')
    junk = bytes([0x13, 0xFF, 0x01, 0x55, 0xFF, 0xFE, 0x05, 0x00, 0x00, 0xAA])
    for i in range(20):
        b.dev.write(junk + p.encode_frame(125, p.pack_string('m%d' % i)))
    b.dev.wait_for(lambda: len(b.backend.published) == 20, what='all 20 messages')
    assert [x[1] for x in b.backend.published] == [p.pack_string('m%d' % i) for i in range(20)]
    assert b.link.stats.bad_versions >= 20
    assert any(t.startswith('Mismatched protocol version in packet (0x01)') for _, t in
               b.backend.logs)
    assert b.backend.has_log('info', 'Protocol version of client is unrecognized (0x01), '
                             'expected Rev 1 (rosserial 0.5+)')
    assert b.backend.has_log('info', 'Wrong checksum for msg length, length 5, dropping message.')


def test_bad_data_checksum(bench_factory):
    b = bench_factory([CHATTER])
    b.wait_log('info', 'Setup publisher on chatter [std_msgs/String]')
    frame = bytearray(p.encode_frame(125, p.pack_string('zz')))
    frame[-1] ^= 0xFF
    b.dev.write(bytes(frame) + p.encode_frame(125, p.pack_string('ok')))
    b.wait_log('info', 'wrong checksum for topic id and msg')
    b.dev.wait_for(lambda: b.backend.published, what='the good frame')
    assert b.backend.published == [('chatter', p.pack_string('ok'))]


def test_truncated_frame_times_out_and_renegotiates(bench_factory):
    b = bench_factory([CHATTER], timeout=0.3)
    b.wait_log('info', 'Setup publisher on chatter [std_msgs/String]')
    requests = b.dev.topic_requests
    b.dev.write(p.encode_frame(125, p.pack_string('cut short'))[:10])
    b.wait_log('warn', 'Last read step: data')
    b.wait_log('info', 'Packet Failed :  Failed to read msg data')
    b.dev.wait_for(lambda: b.dev.topic_requests > requests, what='a new topic request')
    b.dev.send(125, p.pack_string('after'))
    b.dev.wait_for(lambda: b.backend.published, what='the next message')


def test_never_synced_and_lost_sync(bench_factory):
    b = bench_factory([CHATTER], timeout=0.2, answer=False)
    b.wait_log('error', 'Unable to sync with device; possible link problem or link software '
               'version mismatch such as hydro rosserial_python with groovy Arduino')
    assert 'no sync with device' in b.backend.diag
    b.dev.answer = True
    b.dev.send(p.ID_TIME, p.encode_time(0, 0))
    b.wait_log('error', 'Lost sync with device, restarting...')


def test_device_service_and_silent_device_times_out(bench_factory):
    srv_info = [(p.ID_SERVICE_SERVER + p.ID_PUBLISHER,
                 info(125, 'test_srv', 'rosserial_arduino/Test',
                      KNOWN_MD5[('rosserial_arduino/Test', 'response')])),
                (p.ID_SERVICE_SERVER + p.ID_SUBSCRIBER,
                 info(100, 'test_srv', 'rosserial_arduino/Test',
                      KNOWN_MD5[('rosserial_arduino/Test', 'request')]))]
    b = bench_factory(srv_info)
    b.wait_log('info', 'Setup service server on test_srv [rosserial_arduino/Test]')
    b.dev.wait_for(lambda: b.link.services['test_srv'].request_id == 100, what='request id')
    call = b.backend.services['test_srv']

    def answer():
        b.dev.wait_for(lambda: b.dev.frames_on(100), what='the request')
        b.dev.send(125, p.pack_string('pong'))
    t = threading.Thread(target=answer)
    t.start()
    assert call(p.pack_string('ping')) == p.pack_string('pong')
    t.join()
    start = time.monotonic()
    with pytest.raises(DeviceServiceTimeout, match='no response from the device within 0.5 s'):
        call(p.pack_string('nobody home'))
    # the call waited for its timeout (0.5 s) and then gave up: no hang (bound far above it)
    assert 0.45 <= time.monotonic() - start < 60


def test_device_calls_a_ros_service(bench_factory):
    cli_info = [(p.ID_SERVICE_CLIENT + p.ID_PUBLISHER,
                 info(125, 'upper', 'rosserial_arduino/Test',
                      KNOWN_MD5[('rosserial_arduino/Test', 'request')])),
                (p.ID_SERVICE_CLIENT + p.ID_SUBSCRIBER,
                 info(100, 'upper', 'rosserial_arduino/Test',
                      KNOWN_MD5[('rosserial_arduino/Test', 'response')]))]
    b = bench_factory(cli_info)
    b.wait_log('info', 'Setup service client on upper [rosserial_arduino/Test]')
    b.dev.wait_for(lambda: b.link.clients['upper'].response_id == 100, what='response id')
    b.dev.send(125, p.pack_string('shout'))
    b.dev.wait_for(lambda: b.dev.frames_on(100), what='the response')
    assert b.dev.frames_on(100)[0] == p.pack_string('SHOUT')


def test_device_restart_hint_renegotiates(bench_factory):
    b = bench_factory([CHATTER])
    b.wait_log('info', 'Setup publisher on chatter [std_msgs/String]')
    n = b.dev.topic_requests
    b.dev.send(p.ID_PUBLISHER, b'')       # our ros_lib sends this from initNode()
    b.dev.wait_for(lambda: b.dev.topic_requests > n, what='a topic request')


def test_port_vanishing_ends_run_with_an_error(bench_factory):
    b = bench_factory([CHATTER])
    b.wait_log('info', 'Setup publisher on chatter [std_msgs/String]')
    b.dev.close()
    b.thread.join(10)
    assert not b.thread.is_alive()
    assert isinstance(b.error, Exception)
