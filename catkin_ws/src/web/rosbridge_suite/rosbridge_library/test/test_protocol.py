"""The protocol and its capabilities over an in-memory backend (no master): ops, ids echoed,
status messages for bad input, throttling and queues, client services, cleanup."""
import json
import threading
import time

import pytest
from std_msgs.msg import Int32, String

from rosbridge_library.backend import Backend
from rosbridge_library.internal import ros_loader
from rosbridge_library.internal.outgoing_message import OutgoingMessage
from rosbridge_library.protocol import Protocol


class FakeBackend(Backend):
    """Topics loop back: a publish reaches every subscriber of the topic."""

    def __init__(self):
        self.types = {'/chatter': 'std_msgs/String'}
        self.pubs = {}      # topic -> {client: count}
        self.subs = {}      # topic -> {client: callback}
        self.services = {}  # name -> (client, type, handler)
        self.published = []
        self.lock = threading.Lock()

    def now(self):
        return (42, 0)

    def topic_type(self, topic):
        return self.types.get(topic)

    def publisher_type(self, client_id, topic):
        return self.types.get(topic) if client_id in self.pubs.get(topic, {}) else None

    def register_publisher(self, client_id, topic, msg_type, latch=False, queue_size=100):
        if self.types.get(topic, msg_type) != msg_type:
            raise Exception('type conflict on %s' % topic)
        self.types[topic] = msg_type
        d = self.pubs.setdefault(topic, {})
        d[client_id] = d.get(client_id, 0) + 1

    def unregister_publisher(self, client_id, topic):
        d = self.pubs.get(topic, {})
        if client_id in d:
            d[client_id] -= 1
            if d[client_id] <= 0:
                del d[client_id]

    def publish(self, client_id, topic, message):
        self.published.append((topic, message))
        self.deliver(topic, message)

    def deliver(self, topic, message):
        out = OutgoingMessage(message)
        for cb in list(self.subs.get(topic, {}).values()):
            cb(out)

    def subscribe(self, client_id, topic, msg_type, callback):
        self.subs.setdefault(topic, {})[client_id] = callback

    def unsubscribe(self, client_id, topic):
        self.subs.get(topic, {}).pop(client_id, None)

    def service_type(self, service):
        if service == '/add':
            return 'rospy_tutorials/AddTwoInts'
        return self.services[service][1] if service in self.services else None

    def call_service(self, service, srv_type, request, timeout=None):
        if service == '/add':
            if request.a == 99:
                time.sleep(3)
            if request.a < 0:
                raise Exception('service raised: negative')
            resp = ros_loader.get_service_response_instance(srv_type)
            resp.sum = request.a + request.b
            return resp
        return self.services[service][2](request)

    def advertise_service(self, client_id, service, srv_type, handler):
        self.services[service] = (client_id, srv_type, handler)

    def unadvertise_service(self, client_id, service):
        self.services.pop(service, None)

    def finish(self, client_id):
        for d in list(self.pubs.values()) + list(self.subs.values()):
            d.pop(client_id, None)
        for s in [s for s, e in self.services.items() if e[0] == client_id]:
            del self.services[s]

    def registered(self, client_id):
        return (sum(client_id in d for d in self.pubs.values()) +
                sum(client_id in d for d in self.subs.values()) +
                sum(e[0] == client_id for e in self.services.values()))


class Client(object):
    def __init__(self, backend, cid=1, **settings):
        self.frames = []
        self.cond = threading.Condition()
        self.proto = Protocol(cid, backend, self._send, settings)

    def _send(self, data, binary):
        with self.cond:
            self.frames.append(data if binary else json.loads(data))
            self.cond.notify_all()

    def __call__(self, **msg):
        self.proto.incoming(json.dumps(msg))

    def wait(self, pred, timeout=10.0):
        with self.cond:
            assert self.cond.wait_for(lambda: any(pred(f) for f in self.frames), timeout), \
                'no matching frame in %s' % self.frames
            return [f for f in self.frames if pred(f)]

    def ops(self, op):
        return [f for f in self.frames if isinstance(f, dict) and f.get('op') == op]


@pytest.fixture
def backend():
    return FakeBackend()


def test_subscribe_and_publish_loop_back(backend):
    c = Client(backend)
    c(op='subscribe', topic='/chatter', id='s1')
    c(op='advertise', topic='/chatter', type='std_msgs/String', id='a1')
    c(op='publish', topic='/chatter', msg={'data': 'hello'}, id='p1')
    (frame,) = c.ops('publish')
    assert frame == {'op': 'publish', 'topic': '/chatter', 'msg': {'data': 'hello'}}
    assert c.ops('status') == []


@pytest.mark.parametrize('frame,needle', [
    ('{not json', 'Unable to deserialize message from client'),
    ('{"op": "dance", "id": "d1"}', 'Unknown operation: dance'),
    ('{"topic": "/x"}', "Received a message without an op"),
    ('[1, 2]', 'not a JSON object'),
])
def test_bad_frames_get_a_status(backend, frame, needle):
    c = Client(backend)
    c.proto.incoming(frame)
    (status,) = c.ops('status')
    assert status['level'] == 'error' and needle in status['msg'], status
    if '"id"' in frame:
        assert status['id'] == 'd1'


def test_bad_publishes_get_a_status_with_the_id(backend):
    c = Client(backend)
    c(op='advertise', topic='/chatter', type='std_msgs/String')
    c(op='publish', topic='/chatter', msg={'data': 5}, id='p2')
    c(op='publish', topic='/chatter', msg={'text': 'x'}, id='p3')
    c(op='publish', topic='/nowhere', msg={}, id='p4')
    c(op='advertise', topic='/t', type='no_pkg/NoType', id='a5')
    c(op='subscribe', topic='/u', type='std_msgs/Nope', id='s6')
    st = {s['id']: s['msg'] for s in c.ops('status')}
    assert 'requires a string for field data' in st['p2']
    assert 'does not have a field text' in st['p3']
    assert 'Cannot infer topic type for topic /nowhere' in st['p4']
    assert st['a5'].startswith('advertise: Unable to import no_pkg.msg')
    assert 'std_msgs/Nope' in st['s6'] or 'Nope' in st['s6']
    assert backend.published == []


def test_huge_message_is_refused_with_a_status(backend):
    c = Client(backend, max_message_size=1000)
    c(op='advertise', topic='/chatter', type='std_msgs/String')
    c(op='publish', topic='/chatter', msg={'data': 'x' * 5000}, id='big')
    (status,) = c.ops('status')
    assert 'max_message_size 1000' in status['msg']
    assert backend.published == []


def test_set_level_filters_status(backend):
    c = Client(backend)
    c(op='unadvertise', topic='/never')          # a warning: not sent at level error
    assert c.ops('status') == []
    c(op='set_level', level='warning')
    c(op='unadvertise', topic='/never', id='u')
    (status,) = c.ops('status')
    assert status['level'] == 'warning' and status['id'] == 'u'
    c(op='set_level', level='none')
    c(op='dance')
    assert len(c.ops('status')) == 1


def test_throttle_rate_drops_and_queue_length_queues(backend):
    c = Client(backend)
    c(op='subscribe', topic='/chatter', throttle_rate=10000)
    for i in range(5):
        backend.deliver('/chatter', String('m%d' % i))
    assert [f['msg']['data'] for f in c.ops('publish')] == ['m0']
    c2 = Client(backend, cid=2)
    c2(op='subscribe', topic='/chatter', queue_length=2, throttle_rate=50)
    for i in range(6):
        backend.deliver('/chatter', String('q%d' % i))
    got = c2.wait(lambda f: f.get('op') == 'publish' and f['msg']['data'] == 'q5')
    datas = [f['msg']['data'] for f in c2.ops('publish')]
    assert datas[-1] == 'q5' and len(datas) <= 3, datas    # at most the first + a queue of 2
    assert got
    c2.proto.finish()


def test_fragment_size_and_defragmentation(backend):
    c = Client(backend)
    c(op='subscribe', topic='/chatter', fragment_size=20)
    backend.deliver('/chatter', String('x' * 100))
    frags = c.ops('fragment')
    assert len(frags) > 1
    assert json.loads(''.join(f['data'] for f in frags))['msg']['data'] == 'x' * 100
    # the client sends a message in fragments
    text = json.dumps({'op': 'publish', 'topic': '/chatter', 'msg': {'data': 'joined'}})
    c(op='advertise', topic='/chatter', type='std_msgs/String')
    n = 3
    size = len(text) // n + 1
    parts = [text[i * size:(i + 1) * size] for i in range(n)]
    for i in (2, 0, 1):
        c(op='fragment', id='f', data=parts[i], num=i, total=n)
    assert backend.published[-1][1].data == 'joined'


def test_cbor_and_png_subscriptions(backend):
    import cbor2
    from rosbridge_library.internal import wire
    c = Client(backend)
    c(op='subscribe', topic='/chatter', compression='cbor')
    backend.deliver('/chatter', String('c'))
    (raw,) = [f for f in c.frames if isinstance(f, bytes)]
    assert cbor2.loads(raw) == {'op': 'publish', 'topic': '/chatter', 'msg': {'data': 'c'}}
    c2 = Client(backend, cid=2)
    c2(op='subscribe', topic='/chatter', compression='png')
    backend.deliver('/chatter', String('p'))
    (png,) = c2.ops('png')
    assert json.loads(wire.png_decode(png['data']))['msg'] == {'data': 'p'}
    c3 = Client(backend, cid=3)
    c3(op='subscribe', topic='/chatter', compression='cbor-raw')
    backend.deliver('/chatter', String('r'))
    (raw,) = [f for f in c3.frames if isinstance(f, bytes)]
    m = cbor2.loads(raw)['msg']
    assert String().deserialize(m['bytes']).data == 'r' and 'secs' in m
    c4 = Client(backend, cid=4)
    c4(op='subscribe', topic='/chatter', compression='zip', id='z')
    assert 'compression' in c4.ops('status')[0]['msg']


def test_call_service_answers_with_the_id(backend):
    c = Client(backend)
    c(op='call_service', service='/add', args={'a': 2, 'b': 3}, id='call1')
    (resp,) = c.wait(lambda f: f.get('op') == 'service_response')
    assert resp == {'op': 'service_response', 'service': '/add', 'values': {'sum': 5},
                    'result': True, 'id': 'call1'}
    c(op='call_service', service='/add', args=[4, 5], id='call2')
    c.wait(lambda f: f.get('id') == 'call2' and f.get('values') == {'sum': 9})
    c(op='call_service', service='/add', args={'a': -1, 'b': 0}, id='call3')
    (bad,) = c.wait(lambda f: f.get('op') == 'service_response' and f.get('id') == 'call3')
    assert bad['result'] is False and 'negative' in bad['values']
    c.wait(lambda f: f.get('op') == 'status' and f.get('id') == 'call3')
    c(op='call_service', service='/missing', id='call4')
    c.wait(lambda f: f.get('id') == 'call4' and f.get('result') is False)
    c(op='call_service', service='/add', args={'a': 99, 'b': 0}, id='call5', timeout=0.2)
    (late,) = c.wait(lambda f: f.get('op') == 'service_response' and f.get('id') == 'call5')
    assert late['result'] is False and 'timed out after 0.2 s' in late['values']


def test_client_advertised_service(backend):
    provider = Client(backend, cid=1)
    provider(op='advertise_service', service='/echo', type='std_srvs/SetBool')
    assert '/echo' in backend.services
    answer = {}

    def ros_caller():
        req = ros_loader.get_service_request_instance('std_srvs/SetBool')
        req.data = True
        answer['resp'] = backend.services['/echo'][2](req)
    t = threading.Thread(target=ros_caller)
    t.start()
    (call,) = provider.wait(lambda f: f.get('op') == 'call_service')
    assert call['service'] == '/echo' and call['args'] == {'data': True}
    provider(op='service_response', id=call['id'], service='/echo', result=True,
             values={'success': True, 'message': 'done'})
    t.join(10)
    assert answer['resp'].success and answer['resp'].message == 'done'
    provider(op='unadvertise_service', service='/echo')
    assert '/echo' not in backend.services


def test_finish_leaves_nothing(backend):
    c = Client(backend, cid=7)
    c(op='advertise', topic='/chatter', type='std_msgs/String')
    c(op='subscribe', topic='/chatter')
    c(op='advertise', topic='/n', type='std_msgs/Int32')
    c(op='publish', topic='/n', msg={'data': 1})
    c(op='advertise_service', service='/s', type='std_srvs/Empty')
    assert backend.registered(7) == 4
    c.proto.finish()
    assert backend.registered(7) == 0
    backend.deliver('/chatter', String('late'))
    assert c.ops('publish') == []
    assert isinstance(backend.published[0][1], Int32)


def test_queue_thread_stops_on_finish(backend):
    c = Client(backend)
    c(op='subscribe', topic='/chatter', queue_length=3, throttle_rate=10)
    before = threading.active_count()
    c.proto.finish()
    deadline = time.monotonic() + 10
    while threading.active_count() >= before and time.monotonic() < deadline:
        time.sleep(0.01)
    assert threading.active_count() < before


def test_limits_are_counted_and_subscriptions_bounded(backend):
    counted = []
    c = Client(backend, max_message_size=1000, max_subscriptions=2,
               count=lambda name, n=1: counted.append(name))
    c(op='advertise', topic='/chatter', type='std_msgs/String')
    c(op='publish', topic='/chatter', msg={'data': 'x' * 5000}, id='big')
    for i in range(3):
        c(op='subscribe', topic='/t%d' % i, type='std_msgs/String', id='s%d' % i)
    c(op='subscribe', topic='/t0', type='std_msgs/String', id='again')   # same topic: fine
    st = {s.get('id'): s['msg'] for s in c.ops('status')}
    assert set(st) == {None, 's2'}, st     # the oversized frame was never parsed: no id
    assert 'more than max_message_size 1000' in st[None]
    assert 'the most max_client_subscriptions allows: /t2 refused' in st['s2']
    assert counted == ['messages_too_large', 'subscriptions_refused']
    assert sorted(backend.subs) == ['/t0', '/t1']
    assert c.proto.errors == 2      # both reached the client as error statuses


def test_auth_op_without_authentication_is_harmless(backend):
    c = Client(backend)
    c(op='auth', mac='x', client='c', dest='d', rand='r', t=1, level='user', end=2)
    assert c.ops('status') == [] and c.proto.errors == 0
