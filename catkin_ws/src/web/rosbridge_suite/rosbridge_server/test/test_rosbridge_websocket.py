"""rosbridge_websocket.launch for real, with turtlesim, on a private master (one launch for the
whole module): roslibpy drives the turtle, calls /spawn and rosapi, gets and sets parameters
and provides a service that rospy calls; bad input gets a status and disturbs nothing; 20
clients on a 100 Hz topic, one of which never reads; a client's departure leaves nothing."""
import json
import os
import re
import subprocess
import sys
import threading
import xmlrpc.client

import pytest

from course_testing import Proc, RosCore, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from wsclient import WsClient  # noqa: E402

MAX_QUEUE_BYTES = 2 * 1024 * 1024
MAX_MESSAGE_SIZE = 2000000


class Bridge(object):
    def __init__(self, core, launch, turtlesim):
        self.core, self.launch, self.turtlesim = core, launch, turtlesim
        self.master = xmlrpc.client.ServerProxy(core.uri)
        self.port = None

    def param(self, name):
        code, msg, value = self.master.getParam('/test', name)
        return value if code == 1 else None

    def state(self):
        return self.master.getSystemState('/test')[2]

    def registrations(self, node='/rosbridge_websocket'):
        """(published topics, subscribed topics, services) of a node."""
        pubs, subs, srvs = self.state()
        return ({t for t, ns in pubs if node in ns}, {t for t, ns in subs if node in ns},
                {s for s, ns in srvs if node in ns})

    def pid(self, node='/rosbridge_websocket'):
        code, _, uri = self.master.lookupNode('/test', node)
        assert code == 1, 'node %s not registered' % node
        return xmlrpc.client.ServerProxy(uri).getPid('/test')[2]

    def rss_kb(self):
        with open('/proc/%d/status' % self.pid()) as f:
            return int(re.search(r'VmRSS:\s+(\d+)', f.read()).group(1))

    def log(self):
        return self.launch.output()


@pytest.fixture(scope='module')
def bridge(tmp_path_factory):
    tmp = tmp_path_factory.mktemp('rosbridge')
    core = RosCore(log_dir=str(tmp / 'ros_log'))
    core.start()
    launch = turtlesim = None
    try:
        launch = Proc(['roslaunch', 'rosbridge_server', 'rosbridge_websocket.launch', 'port:=0',
                       'unregister_timeout:=1', 'max_message_size:=%d' % MAX_MESSAGE_SIZE,
                       'max_client_queue_bytes:=%d' % MAX_QUEUE_BYTES],
                      env=core.env, log=str(tmp / 'launch.log'))
        turtlesim = Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=core.env,
                         log=str(tmp / 'turtlesim.log'))
        b = Bridge(core, launch, turtlesim)
        b.port = wait_for(lambda: launch.alive() and b.param('/rosbridge_websocket/actual_port'),
                          60, 0.1, 'rosbridge_websocket to listen (~actual_port):\n%s'
                          % launch.output()[-3000:])
        wait_for(lambda: '/rosapi/get_param' in {s for s, _ in b.state()[2]}, 60, 0.1,
                 'rosapi services:\n' + launch.output()[-3000:])
        wait_for(lambda: '/spawn' in {s for s, _ in b.state()[2]}, 60, 0.1,
                 'turtlesim /spawn:\n' + turtlesim.output()[-3000:])
        yield b
    finally:
        for p in (turtlesim, launch):
            if p is not None:
                p.stop()
        core.stop()


@pytest.fixture(scope='module')
def ros(bridge):
    import roslibpy
    client = roslibpy.Ros(host='127.0.0.1', port=bridge.port)
    client.run(timeout=30)
    try:
        yield client
    finally:
        client.close()


def test_roslibpy_turtle_spawn_rosapi(bridge, ros):
    import roslibpy
    assert 'Rosbridge WebSocket server started at ws://' in bridge.log()
    poses = []
    pose_topic = roslibpy.Topic(ros, '/turtle1/pose', 'turtlesim/Pose')
    pose_topic.subscribe(poses.append)
    wait_for(lambda: poses, 30, what='a /turtle1/pose message through rosbridge')
    x0 = poses[-1]['x']
    assert set(poses[-1]) == {'x', 'y', 'theta', 'linear_velocity', 'angular_velocity'}
    cmd = roslibpy.Topic(ros, '/turtle1/cmd_vel', 'geometry_msgs/Twist')

    def moved():
        cmd.publish(roslibpy.Message({'linear': {'x': 2.0, 'y': 0.0, 'z': 0.0},
                                      'angular': {'x': 0.0, 'y': 0.0, 'z': 0.0}}))
        return poses[-1]['x'] > x0 + 0.5
    wait_for(moved, 30, 0.1, 'the turtle to move 0.5 m in x from %.2f (last pose %s)'
             % (x0, poses[-1]))
    pose_topic.unsubscribe()
    cmd.unadvertise()

    spawn = roslibpy.Service(ros, '/spawn', 'turtlesim/Spawn')
    resp = spawn.call(roslibpy.ServiceRequest({'x': 3.0, 'y': 3.0, 'theta': 0.5,
                                               'name': 'webturtle'}), timeout=30)
    assert resp['name'] == 'webturtle'
    topics = wait_for(lambda: '/webturtle/pose' in ros.get_topics() and ros.get_topics(), 30,
                      0.2, '/webturtle/pose in /rosapi/topics')
    assert '/turtle1/cmd_vel' in topics
    assert ros.get_topic_type('/turtle1/pose') == 'turtlesim/Pose'
    raw = roslibpy.Service(ros, '/rosapi/topics_and_raw_types', 'rosapi/TopicsAndRawTypes')
    r = raw.call(roslibpy.ServiceRequest(), timeout=30)
    pose_def = r['typedefs_full_text'][r['topics'].index('/turtle1/pose')]
    assert 'float32 x' in pose_def and 'float32 angular_velocity' in pose_def
    assert '/spawn' in ros.get_services()
    assert '/turtlesim' in ros.get_nodes()


def test_params_through_rosapi(bridge, ros):
    import roslibpy
    p = roslibpy.Param(ros, '/web_test/gain')
    p.set({'kp': 1.5, 'names': ['a', 'b']}, timeout=30)
    assert p.get(timeout=30) == {'kp': 1.5, 'names': ['a', 'b']}
    assert bridge.param('/web_test/gain') == {'kp': 1.5, 'names': ['a', 'b']}
    assert roslibpy.Param(ros, '/turtlesim/background_r').get(timeout=30) == 69
    assert '/web_test/gain/kp' in ros.get_params()
    assert roslibpy.Param(ros, '/no/such/param').get(timeout=30) is None


def test_client_service_called_from_rospy(bridge, ros):
    import roslibpy
    seen = []

    def add(request, response):
        seen.append(request)
        response['sum'] = request['a'] + request['b']
        return True
    service = roslibpy.Service(ros, '/web_add', 'rospy_tutorials/AddTwoInts')
    service.advertise(add)
    wait_for(lambda: '/web_add' in bridge.registrations()[2], 30,
             what='/web_add registered by rosbridge_websocket')
    out = subprocess.run(['rosservice', 'call', '/web_add', '20', '22'], env=bridge.core.env,
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and 'sum: 42' in out.stdout, out.stdout + out.stderr
    assert seen == [{'a': 20, 'b': 22}]
    service.unadvertise()
    wait_for(lambda: '/web_add' not in bridge.registrations()[2], 30,
             what='/web_add gone after unadvertise_service')


def _status(client, mid):
    return client.recv_until(lambda m: m.get('op') == 'status' and m.get('id') == mid)


def test_bad_input_gets_a_status_and_disturbs_nothing(bridge):
    c = WsClient(bridge.port)
    other = WsClient(bridge.port)
    try:
        other.send(op='subscribe', topic='/turtle1/pose', id='watch')
        other.recv_until(lambda m: m.get('op') == 'publish')
        c.send_text('{"op": "publish", "topic": ')
        m = c.recv()
        assert m['op'] == 'status' and m['level'] == 'error'
        assert 'Unable to deserialize message from client' in m['msg']
        c.send(op='fly', id='b1')
        assert 'Unknown operation: fly' in _status(c, 'b1')['msg']
        c.send(op='advertise', topic='/turtle1/cmd_vel', type='geometry_msgs/Twist', id='b2')
        c.send(op='publish', topic='/turtle1/cmd_vel', msg={'linear': {'x': 'fast'}}, id='b2')
        assert 'requires a float64 for field linear.x' in _status(c, 'b2')['msg']
        c.send(op='publish', topic='/turtle1/cmd_vel', msg={'linear': {'q': 1}}, id='b3')
        assert 'does not have a field linear.q' in _status(c, 'b3')['msg']
        c.send(op='subscribe', topic='/nowhere', type='no_such_pkg/Thing', id='b4')
        assert 'no_such_pkg' in _status(c, 'b4')['msg']
        c.send(op='call_service', service='/spawn', args={'name': 'turtle1'}, id='b5')
        got = {}
        while len(got) < 2:
            m = c.recv()
            if m.get('id') == 'b5':
                got[m['op']] = m
        assert got['service_response']['result'] is False
        assert 'call_service /spawn' in got['status']['msg']
        c.send(op='publish', topic='/turtle1/cmd_vel', id='b6',
               msg={'linear': {'x': 0.0}, 'pad': 'x' * (MAX_MESSAGE_SIZE + 1000)})
        m = c.recv_until(lambda m: m.get('op') == 'status')
        assert 'more than max_message_size %d' % MAX_MESSAGE_SIZE in m['msg']
        # the same connection still works, the other client still gets its messages
        c.send(op='call_service', service='/rosapi/get_time', id='ok')
        assert c.recv_until(lambda m: m.get('op') == 'service_response')['result'] is True
        other.recv_until(lambda m: m.get('op') == 'publish')
        assert bridge.launch.alive()
    finally:
        c.close()
        other.close()


def test_many_clients_one_never_reads(bridge):
    count, size, readers = 500, 10000, 19
    clients = [WsClient(bridge.port) for _ in range(readers)]
    slow = WsClient(bridge.port, rcvbuf=4096)
    for c in clients + [slow]:
        c.send(op='subscribe', topic='/counter', type='std_msgs/String')
    rss_before = bridge.rss_kb()
    received = [[] for _ in clients]
    errors = []

    def read(i, c):
        try:
            while len(received[i]) < count:
                op, payload = c.recv_frame()
                m = re.match(rb'.*?"data":"(\d+):', payload[:200])
                if m:
                    received[i].append(int(m.group(1)))
        except Exception as e:   # reported below with the client number
            errors.append('client %d: %s' % (i, e))
    threads = [threading.Thread(target=read, args=(i, c), daemon=True)
               for i, c in enumerate(clients)]
    for t in threads:
        t.start()
    pub = Proc([sys.executable, os.path.join(HERE, 'counter_publisher.py'), str(count), '100',
                str(size), '1'], env=bridge.core.env)
    try:
        for t in threads:
            t.join(120)
        assert not errors, errors
        assert all(r == list(range(count)) for r in received), \
            'readers got %s of %d messages' % ([len(r) for r in received], count)
        rss_after = bridge.rss_kb()
        assert '] outgoing queue full: dropped' in bridge.log(), bridge.log()[-3000:]
    finally:
        pub.stop()
        for c in clients:
            c.close()
        slow.close()
    m = wait_for(lambda: re.search(r'dropped (\d+) outgoing messages in all.*?at most (\d+) '
                                   r'bytes queued', bridge.log()), 30,
                 what='the slow client\'s drop count in the log')
    dropped, high_water = int(m.group(1)), int(m.group(2))
    assert dropped > 0 and high_water <= MAX_QUEUE_BYTES
    # the server holds at most the queue bound for the slow client (plus the interpreter's
    # noise), not the 5 MB that went past it
    assert rss_after - rss_before < 64 * 1024, (rss_before, rss_after)
    wait_for(lambda: '/counter' not in bridge.registrations()[1], 30,
             what='rosbridge to unsubscribe /counter when its clients left')


def test_disconnect_leaves_nothing_behind(bridge):
    c = WsClient(bridge.port)
    c.send(op='advertise', topic='/web_out', type='std_msgs/String')
    c.send(op='subscribe', topic='/web_in', type='std_msgs/String')
    c.send(op='advertise_service', service='/web_srv', type='std_srvs/Trigger')
    wait_for(lambda: all(x in y for x, y in zip(('/web_out', '/web_in', '/web_srv'),
                                                bridge.registrations())),
             30, what='the client\'s publisher, subscriber and service')
    c.close()

    def gone():
        pubs, subs, srvs = bridge.registrations()
        return '/web_out' not in pubs and '/web_in' not in subs and '/web_srv' not in srvs
    wait_for(gone, 30, what='no publisher/subscriber/service left after the client went: %s'
             % (bridge.registrations(),))
    assert bridge.launch.alive()


def test_cbor_and_png_compressions(bridge):
    import cbor2
    from rosbridge_library.internal import wire
    c = WsClient(bridge.port)
    try:
        c.send(op='subscribe', topic='/turtle1/pose', compression='cbor', id='c')
        opcode, payload = c.recv_frame()
        m = cbor2.loads(payload)
        assert opcode == 2 and m['op'] == 'publish' and 'x' in m['msg']
        c.send(op='unsubscribe', topic='/turtle1/pose', id='c')
        c.send(op='subscribe', topic='/turtle1/pose', compression='png', id='p')
        m = c.recv_until(lambda m: m.get('op') == 'png')
        assert 'theta' in json.loads(wire.png_decode(m['data']))['msg']
    finally:
        c.close()
