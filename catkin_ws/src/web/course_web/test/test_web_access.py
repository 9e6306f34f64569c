"""Who can reach the page and rosbridge (web.launch with turtlesim), tested from a second
network namespace that the test makes (a veth pair; traffic stays on this machine):
- address:=0.0.0.0: without the token the page and its files answer 403 and rosbridge closes
  the WebSocket; with it the page, its files, /rosauth and the authenticated WebSocket work;
  a replayed auth message is refused;
- the default bind (127.0.0.1): nothing of it can be reached from the other namespace, and
  from this machine the token works; /rosapi/set_param and delete_param of turtlesim's
  private parameters are refused (protect_node_params), others' still work."""
import json
import os
import random
import subprocess
import sys

import pytest

from course_testing import Proc, RosCore, free_port, wait_for
from course_testing import sim_testing as T

HERE = os.path.dirname(os.path.abspath(__file__))
TOKEN = 'f00dfeed' * 4


def _ip(*args, check=True):
    return subprocess.run(['ip'] + list(args), capture_output=True, text=True, timeout=30,
                          check=check)


@pytest.fixture(scope='module')
def netns():
    """(namespace name, the host's address as seen from it)."""
    tag = '%05x' % random.getrandbits(20)
    ns, host_if, ns_if = 'cwtest' + tag, 'cwh' + tag, 'cwn' + tag
    third, fourth = random.randint(100, 199), 4 * random.randint(1, 60)
    host_ip, ns_ip = '169.254.%d.%d' % (third, fourth + 1), '169.254.%d.%d' % (third, fourth + 2)
    _ip('netns', 'add', ns)
    try:
        _ip('link', 'add', host_if, 'type', 'veth', 'peer', 'name', ns_if)
        _ip('link', 'set', ns_if, 'netns', ns)
        _ip('addr', 'add', host_ip + '/30', 'dev', host_if)
        _ip('link', 'set', host_if, 'up')
        _ip('-n', ns, 'addr', 'add', ns_ip + '/30', 'dev', ns_if)
        _ip('-n', ns, 'link', 'set', ns_if, 'up')
        _ip('-n', ns, 'link', 'set', 'lo', 'up')
        yield ns, host_ip
    finally:
        _ip('link', 'del', host_if, check=False)
        _ip('netns', 'del', ns)


def _from_netns(ns, host, web, bridge, token):
    wsdir = os.path.join(subprocess.check_output(['rospack', 'find', 'rosbridge_server'],
                                                 text=True).strip(), 'test')
    out = subprocess.run(['ip', 'netns', 'exec', ns, sys.executable,
                          os.path.join(HERE, 'netns_client.py'), host, str(web), str(bridge),
                          token or '-', wsdir], capture_output=True, text=True, timeout=180)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads(out.stdout)


class Web(object):
    def __init__(self, tmp, extra):
        self.core = RosCore(log_dir=os.path.join(tmp, 'ros_log')).start()
        self.web, self.bridge = free_port(), free_port()
        env = T.ros_env(self.core)
        self.env = env
        self.procs = [Proc(['roslaunch', 'course_web', 'web.launch', 'port:=%d' % self.web,
                            'rosbridge_port:=%d' % self.bridge,
                            'secret_file:=%s' % os.path.join(tmp, 'secret')] + extra,
                           env=env, log=os.path.join(tmp, 'launch.log')),
                      Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=env,
                           log=os.path.join(tmp, 'turtlesim.log'))]

    def log(self):
        return ''.join(p.output() for p in self.procs)

    def wait_up(self):
        import xmlrpc.client
        master = xmlrpc.client.ServerProxy(self.core.uri)

        def up():
            assert all(p.alive() for p in self.procs), self.log()[-3000:]
            srvs = {s for s, _ in master.getSystemState('/t')[2][2]}
            return {'/authenticate', '/rosapi/set_param', '/spawn'} <= srvs and \
                master.getParam('/t', '/rosbridge_websocket/actual_port')[0] == 1 and \
                master.getParam('/t', '/course_web_server/actual_port')[0] == 1
        wait_for(up, 90, 0.2, 'web.launch and turtlesim:\n' + self.log()[-3000:])

    def stop(self):
        for p in reversed(self.procs):
            p.stop()
        self.core.stop()


def test_open_bind_needs_the_token_from_another_machine(netns, tmp_path):
    ns, host = netns
    w = Web(str(tmp_path), ['address:=0.0.0.0', 'token:=' + TOKEN])
    try:
        w.wait_up()
        r = _from_netns(ns, host, w.web, w.bridge, TOKEN)
        assert r['web_reachable'] is True and r['bridge_reachable'] is True, r
        assert r['page_without_token'] == r['static_without_token'] == \
            r['rosauth_without_token'] == 403, r
        assert str(r['ws_without_auth']).startswith('closed'), r
        assert r['token_visit'] == 302, r
        assert r['page_with_cookie'] == r['static_with_cookie'] == r['rosauth_with_cookie'] \
            == 200, r
        assert r['ws_with_auth'] == '/turtle1/pose', r
        assert str(r['ws_replayed_auth']).startswith('closed'), r
        # the URL with the token is printed on the terminal, never sent to /rosout's log
        assert 'course_web: open http://localhost:%d/?token=%s' % (w.web, TOKEN) in w.log()
        rosout = open(os.path.join(str(tmp_path), 'ros_log', 'rosout.log')).read() \
            if os.path.exists(os.path.join(str(tmp_path), 'ros_log', 'rosout.log')) else ''
        assert TOKEN not in rosout
    finally:
        w.stop()


def test_default_bind_is_local_only(netns, tmp_path):
    ns, host = netns
    w = Web(str(tmp_path), [])
    try:
        w.wait_up()
        r = _from_netns(ns, host, w.web, w.bridge, None)
        assert r['web_reachable'] is not True and r['bridge_reachable'] is not True, r
        # from this machine: the random token printed at start opens the page
        import re
        import urllib.request
        url = wait_for(lambda: re.search(r'course_web: open (http://localhost:\d+/\?token=\w+)',
                                         w.log()), 30, what='the printed URL').group(1)
        token = url.split('token=')[1]
        assert len(token) == 48 and token != TOKEN
        req = urllib.request.Request('http://127.0.0.1:%d/rosauth' % w.web,
                                     headers={'Authorization': 'token ' + token})
        auth = json.loads(urllib.request.urlopen(req, timeout=10).read())
        sys.path.insert(0, os.path.join(subprocess.check_output(
            ['rospack', 'find', 'rosbridge_server'], text=True).strip(), 'test'))
        from wsclient import WsClient
        c = WsClient(w.bridge)
        c.send(**auth)
        answers = {}
        for mid, name in (('own', '/web_test/gain'), ('private', '/turtlesim/background_r')):
            c.send(op='call_service', service='/rosapi/set_param', id=mid,
                   args={'name': name, 'value': '7'})
        c.send(op='call_service', service='/rosapi/delete_param', id='del',
               args={'name': '/turtlesim/background_g'})
        while len(answers) < 3:
            m = c.recv()
            if m.get('op') == 'service_response':
                answers[m['id']] = m
        c.close()
        assert answers['own']['result'] is True, answers
        assert answers['private']['result'] is False and \
            'private parameter of node /turtlesim' in answers['private']['values'], answers
        assert answers['del']['result'] is False, answers
        out = subprocess.run(['rosparam', 'get', '/turtlesim/background_r'], env=w.env,
                             capture_output=True, text=True, timeout=30)
        assert out.stdout.strip() == '69', out
    finally:
        w.stop()
