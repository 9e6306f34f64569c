"""rosbridge_websocket.launch with authenticate:=true and rosauth's ros_mac_authentication on a
private master, with turtlesim: roslibpy without `auth` is closed, with a MAC made from the
secret it publishes and calls, a replayed or expired MAC is refused; 20 clients call rosapi's
topics / nodes / node_details at once and every answer is right. A second launch restricted
to /turtle1/* (globs) and with small limits: what lies outside the globs is refused, and a
flooding or garbage client is cut off while another keeps getting its messages."""
import json
import os
import re
import sys
import threading
import time
import xmlrpc.client

import pytest

from course_testing import Proc, RosCore, wait_for
from rosauth.mac import auth_message, write_secret

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from wsclient import WsClient  # noqa: E402


class Bridge(object):
    def __init__(self, core, procs):
        self.core, self.procs = core, procs
        self.master = xmlrpc.client.ServerProxy(core.uri)
        self.port = None
        self.secret = None

    def param(self, name):
        code, msg, value = self.master.getParam('/test', name)
        return value if code == 1 else None

    def state(self):
        return self.master.getSystemState('/test')[2]

    def log(self):
        return ''.join(p.output() for p in self.procs)

    def auth(self, **kw):
        return auth_message(self.secret, '127.0.0.1', '127.0.0.1', **kw)


def _start(tmp, launch_args, authenticate):
    core = RosCore(log_dir=str(tmp / 'ros_log'))
    core.start()
    procs = []
    try:
        b = Bridge(core, procs)
        if authenticate:
            secret_file = str(tmp / 'secret')
            b.secret = write_secret(secret_file)
            procs.append(Proc(['rosrun', 'rosauth', 'ros_mac_authentication',
                               '_secret_file_location:=' + secret_file], env=core.env,
                              log=str(tmp / 'rosauth.log')))
        procs.append(Proc(['roslaunch', 'rosbridge_server', 'rosbridge_websocket.launch',
                           'port:=0', 'authenticate:=%s' % str(authenticate).lower()]
                          + launch_args, env=core.env, log=str(tmp / 'launch.log')))
        procs.append(Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=core.env,
                          log=str(tmp / 'turtlesim.log')))
        b.port = wait_for(lambda: b.param('/rosbridge_websocket/actual_port'), 60, 0.1,
                          'rosbridge_websocket to listen:\n%s' % b.log()[-3000:])
        needed = {'/rosapi/node_details', '/spawn'} | ({'/authenticate'} if authenticate
                                                       else set())
        wait_for(lambda: needed <= {s for s, _ in b.state()[2]}, 60, 0.1,
                 'services %s:\n%s' % (needed, b.log()[-3000:]))
        yield b
    finally:
        for p in reversed(procs):
            p.stop()
        core.stop()


@pytest.fixture(scope='module')
def bridge(tmp_path_factory):
    yield from _start(tmp_path_factory.mktemp('rosbridge_auth'), [], True)


def _closed(c, timeout=30):
    """The status text the server sent before closing the connection (raises if it stays
    open: the socket timeout)."""
    c.sock.settimeout(timeout)
    texts = []
    try:
        while True:
            m = c.recv()
            if isinstance(m, dict) and m.get('op') == 'status':
                texts.append(m['msg'])
    except ConnectionError as e:
        return ' | '.join(texts) + ' | ' + str(e)


def test_roslibpy_without_auth_is_closed(bridge):
    import roslibpy
    ros = roslibpy.Ros(host='127.0.0.1', port=bridge.port)
    closed = threading.Event()
    ros.on('close', lambda *_: closed.set())
    ros.run(timeout=30)
    try:
        got = []
        roslibpy.Topic(ros, '/turtle1/pose', 'turtlesim/Pose').subscribe(got.append)
        assert closed.wait(30), 'the connection stayed open without auth'
        assert got == []
    finally:
        ros.close()
    wait_for(lambda: re.search(r'Client \d+ did not authenticate\. Closing connection\.',
                               bridge.log()), 30, what="the original's refusal line logged")


def test_raw_client_first_op_not_auth_closed_with_status(bridge):
    c = WsClient(bridge.port)
    c.send(op='call_service', service='/rosapi/get_time', id='x')
    text = _closed(c)
    assert 'authentication required' in text and "first op was 'call_service'" in text, text
    c.close()


def test_roslibpy_with_mac_publishes_and_calls(bridge):
    import roslibpy
    ros = roslibpy.Ros(host='127.0.0.1', port=bridge.port)
    a = bridge.auth()
    ros.authenticate(a['mac'], a['client'], a['dest'], a['rand'], a['t'], a['level'], a['end'])
    ros.run(timeout=30)
    try:
        poses = []
        pose_topic = roslibpy.Topic(ros, '/turtle1/pose', 'turtlesim/Pose')
        pose_topic.subscribe(poses.append)
        wait_for(lambda: poses, 30, what='a pose through the authenticated connection')
        x0 = poses[-1]['x']
        cmd = roslibpy.Topic(ros, '/turtle1/cmd_vel', 'geometry_msgs/Twist')

        def moved():
            cmd.publish(roslibpy.Message({'linear': {'x': 2.0, 'y': 0.0, 'z': 0.0},
                                          'angular': {'x': 0.0, 'y': 0.0, 'z': 0.0}}))
            return poses[-1]['x'] > x0 + 0.5
        wait_for(moved, 30, 0.1, 'the turtle to move')
        spawn = roslibpy.Service(ros, '/spawn', 'turtlesim/Spawn')
        resp = spawn.call(roslibpy.ServiceRequest({'x': 3.0, 'y': 3.0, 'theta': 0.0,
                                                   'name': 'authturtle'}), timeout=30)
        assert resp['name'] == 'authturtle'
    finally:
        ros.close()
    assert 'has authenticated.' in bridge.log()


def test_replayed_and_expired_macs_refused(bridge):
    a = bridge.auth()
    c = WsClient(bridge.port)
    c.send(**a)
    c.send(op='call_service', service='/rosapi/get_time', id='t1')
    assert c.recv_until(lambda m: m.get('id') == 't1')['result'] is True
    c.close()
    again = WsClient(bridge.port)              # the same MAC a second time
    again.send(**a)
    again.send(op='call_service', service='/rosapi/get_time', id='t2')
    text = _closed(again)
    assert 'authentication required' in text, text
    again.close()
    old = WsClient(bridge.port)                # made a minute ago
    old.send(**bridge.auth(now=time.time() - 60))
    old.send(op='call_service', service='/rosapi/get_time', id='t3')
    assert 'authentication required' in _closed(old)
    old.close()
    wrong = WsClient(bridge.port)              # another secret
    wrong.send(**auth_message('0123456789abcdef', '127.0.0.1', '127.0.0.1'))
    assert 'authentication required' in _closed(wrong)
    wrong.close()
    ok = WsClient(bridge.port)                 # a fresh one still works
    ok.send(**bridge.auth())
    ok.send(op='call_service', service='/rosapi/get_time', id='t4')
    assert ok.recv_until(lambda m: m.get('id') == 't4')['result'] is True
    ok.close()
    log = bridge.log()
    assert 'replay' in log and 'away from now' in log and 'wrong MAC' in log


def test_twenty_clients_call_rosapi_at_once(bridge):
    """rosapi answers concurrent requests on threads: every answer must be right."""
    pubs, subs, srvs = bridge.state()
    nodes = sorted({n for section in (pubs, subs, srvs) for _, ns in section for n in ns})
    topics = sorted(t for t, _ in bridge.master.getTopicTypes('/test')[2])
    ts_pubs = sorted(t for t, ns in pubs if '/turtlesim' in ns)
    clients = []
    for _ in range(20):
        c = WsClient(bridge.port)
        c.send(**bridge.auth())
        clients.append(c)
    rounds = 5
    errors = []
    barrier = threading.Barrier(len(clients))

    def run(i, c):
        try:
            barrier.wait(30)
            for r in range(rounds):
                for name, args in (('topics', {}), ('nodes', {}),
                                   ('node_details', {'node': '/turtlesim'})):
                    c.send(op='call_service', service='/rosapi/' + name, args=args,
                           id='%s-%d' % (name, r))
            answers = {}
            while len(answers) < 3 * rounds:
                m = c.recv()
                if isinstance(m, dict) and m.get('op') == 'service_response':
                    answers[m['id']] = m
            for mid, m in answers.items():
                if not m['result']:
                    errors.append('client %d %s: %s' % (i, mid, m['values']))
                elif mid.startswith('topics') and not set(topics) <= set(m['values']['topics']):
                    errors.append('client %d %s: topics %s' % (i, mid, m['values']))
                elif mid.startswith('nodes') and m['values']['nodes'] != nodes:
                    errors.append('client %d %s: nodes %s' % (i, mid, m['values']))
                elif mid.startswith('node_details') and \
                        m['values']['publishing'] != ts_pubs:
                    errors.append('client %d %s: %s' % (i, mid, m['values']))
        except Exception as e:   # reported with the client number
            errors.append('client %d: %r' % (i, e))
    threads = [threading.Thread(target=run, args=(i, c), daemon=True)
               for i, c in enumerate(clients)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(180)
    for c in clients:
        c.close()
    assert not errors, '%d errors, first: %s' % (len(errors), errors[:3])
    log = bridge.log()
    for needle in ('CannotSendRequest', 'ResponseNotReady', 'Bad file descriptor'):
        assert needle not in log, log[-3000:]


# ------------------------------------------------------------------ globs and limits
@pytest.fixture(scope='module')
def restricted(tmp_path_factory):
    yield from _start(tmp_path_factory.mktemp('rosbridge_globs'),
                      ['topics_glob:=[/turtle1/*]', 'services_glob:=[/turtle1/*]',
                       'params_glob:=[/turtle1/*]', 'max_connections_per_address:=4',
                       'max_client_subscriptions:=2', 'max_client_bytes_per_second:=1000000',
                       'max_client_errors_per_second:=2'], False)


def _status(c, mid):
    return c.recv_until(lambda m: m.get('op') == 'status' and m.get('id') == mid)


def test_globs_keep_a_client_inside_turtle1(restricted):
    c = WsClient(restricted.port)
    watch = WsClient(restricted.port)
    try:
        c.send(op='set_level', level='warning')
        watch.send(op='set_level', level='warning')
        watch.send(op='subscribe', topic='/cmd_vel', type='geometry_msgs/Twist', id='w')
        assert 'No subscription permission for topic: /cmd_vel' in _status(watch, 'w')['msg']
        c.send(op='advertise', topic='/cmd_vel', type='geometry_msgs/Twist', id='a1')
        assert 'No advertise permission for topic: /cmd_vel' in _status(c, 'a1')['msg']
        c.send(op='publish', topic='/cmd_vel', msg={'linear': {'x': 1.0}}, id='p1')
        assert 'No publish permission for topic: /cmd_vel' in _status(c, 'p1')['msg']
        assert '/cmd_vel' not in {t for t, _ in restricted.state()[0]}
        c.send(op='call_service', service='/rosapi/set_param', id='s1',
               args={'name': '/turtle1/x', 'value': '1'})
        r = c.recv_until(lambda m: m.get('op') == 'service_response' and m.get('id') == 's1')
        assert r['result'] is False and 'No permission to call service' in r['values']
        assert restricted.param('/turtle1/x') is None
        # inside the globs everything works
        c.send(op='subscribe', topic='/turtle1/pose', type='turtlesim/Pose', id='ok')
        c.recv_until(lambda m: m.get('op') == 'publish' and m['topic'] == '/turtle1/pose')
        c.send(op='call_service', service='/turtle1/teleport_absolute', id='s2',
               args={'x': 2.0, 'y': 2.0, 'theta': 0.0})
        assert c.recv_until(lambda m: m.get('id') == 's2' and
                            m.get('op') == 'service_response')['result'] is True
    finally:
        c.close()
        watch.close()


def test_limits_status_and_cut_off_without_disturbing_others(restricted):
    other = WsClient(restricted.port)
    other.send(op='subscribe', topic='/turtle1/pose', type='turtlesim/Pose')
    other.recv_until(lambda m: m.get('op') == 'publish')
    clients = [WsClient(restricted.port) for _ in range(3)]
    # the flooder and the garbage sender come from addresses of their own (the incoming
    # budgets are per address: a client cut off finds its budget spent when it reconnects)
    flood = WsClient(restricted.port, source='127.0.0.2')
    garbage = WsClient(restricted.port, source='127.0.0.3')
    try:
        # a 5th connection from this address is refused with a status
        fifth = WsClient(restricted.port)
        assert 'max_connections_per_address' in _closed(fifth)
        fifth.close()
        # a third subscription is refused with a status
        c = clients[0]
        c.send(op='subscribe', topic='/turtle1/pose', type='turtlesim/Pose', id='1')
        c.send(op='subscribe', topic='/turtle1/color_sensor', type='turtlesim/Color', id='2')
        c.send(op='subscribe', topic='/turtle1/cmd_vel', type='geometry_msgs/Twist', id='3')
        assert 'max_client_subscriptions' in _status(c, '3')['msg']
        # a flood of large messages: cut off, and so is its next connection
        flood.sock.settimeout(30)
        big = json.dumps({'op': 'publish', 'topic': '/turtle1/cmd_vel',
                          'msg': {'linear': {'x': 0.0}}, 'pad': 'x' * 100000})
        try:
            for _ in range(100):
                flood.send_text(big)
        except OSError:
            pass
        assert 'more than 1000000 bytes a second' in _closed(flood)
        again = WsClient(restricted.port, source='127.0.0.2')
        again.send_text(big)
        assert 'cut off' in _closed(again)
        again.close()
        # garbage: cut off
        try:
            for _ in range(100):
                garbage.send_text('{nonsense')
        except OSError:
            pass
        assert 'bad messages a second' in _closed(garbage)
        # the other client still gets its poses, and this address can still talk
        n = [0]
        deadline = time.monotonic() + 30

        def count(m):
            n[0] += 1
            return n[0] >= 20 or time.monotonic() > deadline
        other.recv_until(lambda m: m.get('op') == 'publish' and count(m))
        assert n[0] >= 20
        c.send(op='call_service', service='/turtle1/teleport_relative', id='t',
               args={'linear': 0.0, 'angular': 0.0})
        assert c.recv_until(lambda m: m.get('id') == 't' and
                            m.get('op') == 'service_response')['result'] is True
        limits = wait_for(lambda: _limits(restricted), 30, 0.2, '~limits')
        assert limits['connections_refused'] >= 1 and limits['clients_cut_off'] >= 3 and \
            limits['subscriptions_refused'] >= 1, limits
    finally:
        other.close()
        flood.close()
        garbage.close()
        for c in clients:
            c.close()


def _limits(bridge):
    import subprocess
    out = subprocess.run(['rostopic', 'echo', '-n', '1', '/rosbridge_websocket/limits'],
                         env=bridge.core.env, capture_output=True, text=True,
                         timeout=60).stdout
    values = {}
    key = None
    for line in out.splitlines():
        line = line.strip()
        if line.startswith('key:'):
            key = line.split(':', 1)[1].strip().strip('"')
        elif line.startswith('value:') and key:
            values[key] = int(line.split(':', 1)[1].strip().strip('"'))
    if values.get('clients_cut_off', 0) < 3:
        return None
    return values
