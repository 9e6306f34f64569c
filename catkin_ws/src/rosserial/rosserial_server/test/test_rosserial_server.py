"""rosserial_server as its users run it, with a private roscore:
- socket.launch (socket_node, TCP) with a host client built from rosserial_client's ros_lib over
  a TCP hardware class: a device publisher reaches ROS, a ROS message reaches the device's
  subscriber, the device serves a service, calls a ROS service, reads parameters;
- serial.launch (serial_node) with sketches on the emulated Mega (simavr) on a pty: hello_world,
  and adc_service (a workspace message, a device service, a `~` parameter); the port vanishing
  and coming back is reopened."""
import os
import shutil
import subprocess
import sys

import pytest
import rospkg

from course_testing import Proc, RosCore, wait_for
from course_testing.proc import free_port

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, *['..'] * 5))


@pytest.fixture
def core(tmp_path):
    c = RosCore(log_dir=str(tmp_path / 'ros_log'))
    c.start()
    yield c
    c.stop()


@pytest.fixture(scope='module')
def host_client(tmp_path_factory):
    from rosserial_client.make_library import PRIMITIVES_GENERIC, make_library
    tmp = tmp_path_factory.mktemp('client')
    rp = rospkg.RosPack()
    lib = str(tmp / 'ros_lib')
    pkgs = dict((p, rp.get_path(p)) for p in ('std_msgs', 'std_srvs', 'rosserial_msgs'))
    assert make_library(lib, [], PRIMITIVES_GENERIC, packages=pkgs) == []
    exe = str(tmp / 'host_client')
    gxx = shutil.which('g++')
    assert gxx, 'g++ is missing'
    p = subprocess.run([gxx, '-std=c++17', '-Wall', '-Wextra', '-Werror', '-Wno-unused-parameter',
                        '-I', lib, os.path.join(HERE, 'host_client.cpp'),
                        os.path.join(lib, 'time.cpp'), os.path.join(lib, 'duration.cpp'),
                        '-o', exe], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-4000:]
    return exe


def echo(core, topic, timeout=90):
    p = subprocess.run(['rostopic', 'echo', '-n', '1', topic], env=core.env,
                       capture_output=True, text=True, timeout=timeout)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_socket_node_with_a_tcp_client(core, host_client, tmp_path):
    port = free_port()
    subprocess.run(['rosparam', 'set', 'int_value', '1'], env=core.env, check=True, timeout=60)
    subprocess.run(['rosparam', 'set', 'float_value', '0.5'], env=core.env, check=True, timeout=60)
    subprocess.run(['rosparam', 'set', 'bool_value', 'true'], env=core.env, check=True, timeout=60)
    subprocess.run(['rosparam', 'set', 'string_value', 'sample text'], env=core.env, check=True,
                   timeout=60)
    server = Proc(['roslaunch', 'rosserial_server', 'socket.launch', 'port:=%d' % port],
                  env=core.env, log=str(tmp_path / 'server.log'))
    ros_srv = Proc([sys.executable, '-c',
                    'import rospy\nfrom std_srvs.srv import Trigger, TriggerResponse\n'
                    'rospy.init_node("ros_srv")\n'
                    'rospy.Service("ros_srv", Trigger, lambda r: TriggerResponse(True, "hello from ROS"))\n'
                    'rospy.spin()\n'], env=core.env, log=str(tmp_path / 'ros_srv.log'))
    client = Proc([host_client, str(port)], env=dict(core.env, CALL_ROS_SRV='1'),
                  log=str(tmp_path / 'client.log'))
    try:
        wait_for(lambda: 'Setup publisher on chatter [std_msgs/String]' in server.output(), 90,
                 what='negotiation in the server log:\n' + server.output()[-3000:])
        assert 'data: "from-rosserial-client"' in echo(core, '/chatter')
        wait_for(lambda: 'params ' in client.output(), 60, what='params in the client output')
        assert 'params 1 1 0.5 1 sample text' in client.output(), client.output()
        # ROS -> device subscriber -> device publisher
        pub = Proc(['rostopic', 'pub', '-r', '2', '/words', 'std_msgs/String', 'data: hi device'],
                   env=core.env)
        try:
            assert 'data: "echo: hi device"' in echo(core, '/echo')
        finally:
            pub.stop()
        # a service served by the device
        p = subprocess.run(['rosservice', 'call', '/test_srv'], env=core.env, capture_output=True,
                           text=True, timeout=90)
        assert p.returncode == 0, p.stderr
        assert 'success: True' in p.stdout and 'served by the client' in p.stdout, p.stdout
        # the device calls a ROS service
        wait_for(lambda: 'called hello from ROS' in client.output(), 90,
                 what='the device calling ros_srv:\n' + client.output()[-2000:])
        assert client.alive() and server.alive()
    finally:
        client.stop()
        ros_srv.stop()
        server.stop()


def test_udp_socket_node_with_a_udp_client(core, host_client, tmp_path):
    """udp_socket_node (udp_socket.launch's node, with its own server port so both ends fit on
    one host): the client is started after the server, which keeps asking for topics while
    nobody listens; publish, subscribe and a device service over datagrams."""
    server_port, client_port = free_port(), free_port()
    server = Proc(['rosrun', 'rosserial_server', 'udp_socket_node',
                   '_server_port:=%d' % server_port, '_client_port:=%d' % client_port,
                   '_client_addr:=127.0.0.1'], env=core.env, log=str(tmp_path / 'server.log'))
    client = None
    try:
        wait_for(lambda: 'Requesting topics' in server.output(), 90,
                 what='udp_socket_node asking for topics:\n' + server.output()[-2000:])
        client = Proc([host_client, 'udp:%d:%d' % (server_port, client_port)], env=core.env,
                      log=str(tmp_path / 'client.log'))
        wait_for(lambda: 'Setup publisher on chatter [std_msgs/String]' in server.output(), 90,
                 what='negotiation over UDP:\n' + server.output()[-3000:])
        assert 'data: "from-rosserial-client"' in echo(core, '/chatter')
        pub = Proc(['rostopic', 'pub', '-r', '2', '/words', 'std_msgs/String', 'data: hi udp'],
                   env=core.env)
        try:
            assert 'data: "echo: hi udp"' in echo(core, '/echo')
        finally:
            pub.stop()
        p = subprocess.run(['rosservice', 'call', '/test_srv'], env=core.env, capture_output=True,
                           text=True, timeout=90)
        assert p.returncode == 0, p.stderr
        assert 'served by the client' in p.stdout, p.stdout
        assert client.alive() and server.alive()
    finally:
        if client is not None:
            client.stop()
        server.stop()


def test_require_re_requests_topics_until_the_device_has_them(core, host_client, tmp_path):
    """~require/publishers and ~require/subscribers: a device without one of them is asked for
    its topics again (the original's warning), one with all of them is left alone."""
    warning = ('Connected client failed to establish the publishers and subscribers dictated '
               'by require parameter. Re-requesting topics.')
    for name, pubs, ok in (('missing', ['chatter', 'no_such_topic'], False),
                           ('present', ['chatter', '/echo'], True)):
        subprocess.run(['rosparam', 'set', '/rosserial_server/require',
                        '{publishers: %s, subscribers: [words]}' % pubs], env=core.env,
                       check=True, timeout=60)
        port = free_port()
        server = Proc(['rosrun', 'rosserial_server', 'socket_node', '_port:=%d' % port,
                       '__name:=rosserial_server'], env=core.env,
                      log=str(tmp_path / ('server-%s.log' % name)))
        client = Proc([host_client, str(port)], env=core.env,
                      log=str(tmp_path / ('client-%s.log' % name)))
        try:
            wait_for(lambda: server.output().count('Setup publisher on chatter') >= 2 if not ok
                     else 'Setup subscriber on words' in server.output(), 90,
                     what='negotiation (%s):\n%s' % (name, server.output()[-3000:]))
            if ok:
                # 20 messages of the device's 10 Hz chatter after negotiation: 2 s of its
                # output, past the check 1 s after the topic request
                p = subprocess.run(['rostopic', 'echo', '-n', '20', '/chatter'], env=core.env,
                                   capture_output=True, text=True, timeout=120)
                assert p.stdout.count('from-rosserial-client') == 20, p.stderr
                assert warning not in server.output(), server.output()[-3000:]
            else:
                assert warning in server.output(), server.output()[-3000:]
        finally:
            client.stop()
            server.stop()


def test_udp_socket_node_refuses_a_bad_address(core, tmp_path):
    p = subprocess.run(['rosrun', 'rosserial_server', 'udp_socket_node', '_client_addr:=nowhere',
                        '__name:=udp_bad'], env=core.env, capture_output=True, text=True,
                       timeout=90)
    assert p.returncode == 1
    assert "~client_addr: 'nowhere' is not an IPv4 address" in p.stdout + p.stderr


def test_serial_node_with_sketches_in_the_simulator(core, tmp_path):
    sys.path.insert(0, os.path.join(REPO, 'firmware', 'hil'))
    import harness
    elf = harness.build('adc_service')
    # serial_node's private parameter, read once by the sketch with getParam("~adc_offset")
    subprocess.run(['rosparam', 'set', '/rosserial_server/adc_offset', '7'], env=core.env,
                   check=True, timeout=60)
    sim = harness.Simulation(elf)
    server = Proc(['roslaunch', 'rosserial_server', 'serial.launch', 'port:=%s' % sim.pty],
                  env=core.env, log=str(tmp_path / 'server.log'))
    try:
        wait_for(lambda: 'Setup service server on test_srv [rosserial_arduino/Test]'
                 in server.output(), 90, what='negotiation:\n' + server.output()[-3000:])
        assert 'Setup publisher on adc [rosserial_arduino/Adc]' in server.output()
        # the first message may precede the parameter's reply
        wait_for(lambda: 'adc5: 7' in echo(core, '/adc'), 90, what='~adc_offset applied')
        p = subprocess.run(['rosservice', 'call', '/test_srv', 'input: "rosserial"'],
                           env=core.env, capture_output=True, text=True, timeout=90)
        assert p.returncode == 0, p.stderr
        assert 'output: "lairessor"' in p.stdout, p.stdout
        # an MCU reset: renegotiated without restarting the server
        before = server.output().count('Setup publisher on adc')
        sim.command('reset')
        wait_for(lambda: server.output().count('Setup publisher on adc') > before, 90,
                 what='renegotiation after the reset:\n' + server.output()[-2000:])
        assert 'adc0:' in echo(core, '/adc')
        assert server.alive()
    finally:
        server.stop()
        sim.stop()


def test_serial_node_reopens_the_port_for_each_new_device(core, host_client, tmp_path):
    """As the original rosserial_test's serial fixture: serial_node is started on a path that
    does not exist yet; each client makes a new pty and symlinks its slave there, talks, and
    closes it; the next one is served without restarting serial_node."""
    link = str(tmp_path / 'rosserial_pty')
    server = Proc(['roslaunch', 'rosserial_server', 'serial.launch', 'port:=%s' % link],
                  env=core.env, log=str(tmp_path / 'server.log'))
    try:
        wait_for(lambda: 'Unable to open port %s' % link in server.output(), 90,
                 what='serial_node waiting for the port')
        for n in (1, 2):
            client = Proc([host_client, link], env=core.env, log=str(tmp_path / ('c%d.log' % n)))
            try:
                wait_for(lambda: server.output().count('Setup subscriber on words') >= n, 90,
                         what='negotiation %d:\n%s' % (n, server.output()[-2000:]))
                assert 'data: "from-rosserial-client"' in echo(core, '/chatter')
                pub = Proc(['rostopic', 'pub', '-r', '2', '/words', 'std_msgs/String',
                            'data: pty %d' % n], env=core.env)
                try:
                    assert 'data: "echo: pty %d"' % n in echo(core, '/echo')
                finally:
                    pub.stop()
            finally:
                client.stop()
            wait_for(lambda: server.output().count('closed') >= n, 60,
                     what='serial_node noticing the pty closed')
        assert server.alive()
    finally:
        server.stop()


class PtyTcpRelay(object):
    """The emulated board's UART carried over TCP, as a serial-to-Wi-Fi bridge (ESP-Link and the
    like) would: bytes from the pty go to the TCP server and back."""

    def __init__(self, pty, port):
        import socket
        import termios
        import threading
        import tty
        self.fd = os.open(pty, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(self.fd, termios.TCSANOW)
        self.sock = socket.create_connection(('127.0.0.1', port), timeout=30)
        self.sock.setblocking(True)
        self.stop_flag = False
        self.threads = [threading.Thread(target=self._up, daemon=True),
                        threading.Thread(target=self._down, daemon=True)]
        for t in self.threads:
            t.start()

    def _up(self):
        import select
        while not self.stop_flag:
            r, _, _ = select.select([self.fd], [], [], 0.1)
            if r:
                try:
                    data = os.read(self.fd, 4096)
                    self.sock.sendall(data)
                except OSError:
                    return

    def _down(self):
        self.sock.settimeout(0.1)
        import socket
        while not self.stop_flag:
            try:
                data = self.sock.recv(4096)
            except socket.timeout:
                continue
            except OSError:
                return
            if not data:
                return
            os.write(self.fd, data)

    def close(self):
        self.stop_flag = True
        for t in self.threads:
            t.join(2)
        self.sock.close()
        os.close(self.fd)


def test_socket_node_with_a_sketch_in_the_simulator_over_tcp(core, tmp_path):
    sys.path.insert(0, os.path.join(REPO, 'firmware', 'hil'))
    import harness
    port = free_port()
    server = Proc(['roslaunch', 'rosserial_server', 'socket.launch', 'port:=%d' % port],
                  env=core.env, log=str(tmp_path / 'server.log'))
    sim = harness.Simulation(harness.build('hello_world'))
    relay = None
    try:
        wait_for(lambda: 'Listening on port %d' % port in server.output(), 90,
                 what='socket_node listening')
        relay = PtyTcpRelay(sim.pty, port)
        wait_for(lambda: 'Setup publisher on chatter [std_msgs/String]' in server.output(), 90,
                 what='the Mega negotiating over TCP')
        assert 'data: "hello world!"' in echo(core, '/chatter')
        assert server.alive()
    finally:
        if relay is not None:
            relay.close()
        server.stop()
        sim.stop()
