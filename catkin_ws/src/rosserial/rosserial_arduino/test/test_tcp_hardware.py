"""ArduinoTcpHardware.h (ros.h on ESP8266/ESP32): the Esp8266HelloWorld example, compiled for the
host against a shim of the ESP core (esp_shim/: WiFiClient on POSIX sockets), talks to
rosserial_server's socket.launch: chatter reaches ROS, and after the server is restarted the
sketch reconnects by itself and chatter comes back."""
import os
import shutil
import subprocess

import rospkg

from course_testing import Proc, wait_for
from course_testing.proc import free_port
from rosserial_client.make_library import PRIMITIVES_ARDUINO, make_library

HERE = os.path.dirname(os.path.abspath(__file__))
SHIM = os.path.join(HERE, 'esp_shim')
ARDUINO_LIB = os.path.join(HERE, '..', 'src', 'ros_lib')


def build(tmp_path):
    rp = rospkg.RosPack()
    lib = str(tmp_path / 'ros_lib')
    pkgs = dict((p, rp.get_path(p)) for p in ('std_msgs', 'rosserial_msgs'))
    assert make_library(lib, [ARDUINO_LIB], PRIMITIVES_ARDUINO, packages=pkgs) == []
    exe = str(tmp_path / 'esp_hello')
    gxx = shutil.which('g++')
    assert gxx, 'g++ is missing'
    p = subprocess.run([gxx, '-std=c++17', '-Wall', '-Wextra', '-Werror', '-Wno-unused-parameter',
                        '-DESP8266', '-I', SHIM, '-I', lib, '-x', 'c++',
                        os.path.join(lib, 'examples', 'Esp8266HelloWorld', 'Esp8266HelloWorld.ino'),
                        '-x', 'none', os.path.join(SHIM, 'main.cpp'), os.path.join(lib, 'time.cpp'),
                        os.path.join(lib, 'duration.cpp'), '-o', exe],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-4000:]
    return exe


def echo(core):
    p = subprocess.run(['rostopic', 'echo', '-n', '1', '/chatter'], env=core.env,
                       capture_output=True, text=True, timeout=90)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_esp_sketch_over_tcp_reconnects(roscore, tmp_path):
    exe = build(tmp_path)
    port = free_port()
    launch = ['roslaunch', 'rosserial_server', 'socket.launch', 'port:=%d' % port]
    server = Proc(launch, env=roscore.env, log=str(tmp_path / 'server1.log'))
    sketch = Proc([exe], env=dict(roscore.env, SHIM_PORT=str(port)),
                  log=str(tmp_path / 'sketch.log'))
    try:
        wait_for(lambda: 'Setup publisher on chatter [std_msgs/String]' in server.output(), 90,
                 what='the sketch negotiating with socket_node')
        assert 'IP address: 127.0.0.1' in sketch.output()
        assert 'data: "hello world!"' in echo(roscore)
        server.stop()
        server = Proc(launch, env=roscore.env, log=str(tmp_path / 'server2.log'))
        wait_for(lambda: 'Setup publisher on chatter' in server.output(), 90,
                 what='the sketch reconnecting to the restarted server:\n' + sketch.output()[-500:])
        assert 'connected 2' in sketch.output()
        assert 'data: "hello world!"' in echo(roscore)
    finally:
        sketch.stop()
        server.stop()
