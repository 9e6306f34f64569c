"""rosserial_server and rosserial_client as the original rosserial_test suite uses them: a host
ros_lib generated through rosserial_client.make_library's module API (rosserial_client_copy_files,
rosserial_generate, the data type mapping), its includes rewritten to "rosserial/...", included
inside `namespace rosserial` next to roscpp in one gtest program; publish, subscribe, a device
service server and parameters against socket_node (TCP) and serial_node (a new pty per test case,
symlinked where serial_node looks), each launched with the package's launch file."""
import os
import shutil
import subprocess

import pytest

from course_testing import Proc
from course_testing.proc import free_port

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'harness')
REPO = os.path.abspath(os.path.join(HERE, *['..'] * 6))
PARAMS = (('int_value', '1'), ('float_value', '0.5'), ('bool_value', 'true'),
          ('string_value', 'sample text'))


@pytest.fixture(scope='module')
def harness(tmp_path_factory):
    tmp = tmp_path_factory.mktemp('harness')
    p = subprocess.run(['/usr/bin/python3', os.path.join(HERE, 'generate.py'), str(tmp)],
                       capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    gxx = shutil.which('g++')
    assert gxx, 'g++ is missing'
    exe = str(tmp / 'pubsub_test')
    p = subprocess.run([gxx, '-std=c++17', '-Wall', '-Wextra', '-Werror', '-Wno-unused-parameter',
                        '-I', HERE, '-I', str(tmp),
                        '-I', os.path.join(REPO, 'catkin_ws', 'devel', 'include'),
                        os.path.join(HERE, 'pubsub_test.cpp'), '-o', exe, '-lroscpp',
                        '-lrosconsole', '-lroscpp_serialization', '-lrostime', '-lxmlrpcpp',
                        '-lcpp_common', '-lboost_system', '-lgtest', '-pthread'],
                       capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stderr[-4000:]
    return exe


def run(core, exe, tmp_path, launch, launch_args, test_args):
    for k, v in PARAMS:
        subprocess.run(['rosparam', 'set', k, v], env=core.env, check=True, timeout=60)
    server = Proc(['roslaunch', 'rosserial_server', launch] + launch_args, env=core.env,
                  log=str(tmp_path / 'server.log'))
    try:
        p = subprocess.run([exe] + test_args, env=core.env, capture_output=True, text=True,
                           timeout=300)
        assert p.returncode == 0 and '[  PASSED  ] 3 tests.' in p.stdout, \
            p.stdout[-3000:] + '\nserver:\n' + server.output()[-3000:]
        assert server.alive()
    finally:
        server.stop()


def test_socket_node(roscore, harness, tmp_path):
    port = free_port()
    run(roscore, harness, tmp_path, 'socket.launch', ['port:=%d' % port],
        ['_mode:=socket', '_tcp_port:=%d' % port])


def test_serial_node(roscore, harness, tmp_path):
    link = str(tmp_path / 'rosserial_pty')
    run(roscore, harness, tmp_path, 'serial.launch', ['port:=%s' % link],
        ['_mode:=serial', '_port:=%s' % link])


def test_rosserial_python_tcp_mode(roscore, harness, tmp_path):
    """The same client against rosserial_python's serial_node.py in tcp mode."""
    port = free_port()
    for k, v in PARAMS:
        subprocess.run(['rosparam', 'set', k, v], env=roscore.env, check=True, timeout=60)
    node = Proc(['rosrun', 'rosserial_python', 'serial_node.py', 'tcp', str(port)],
                env=roscore.env, log=str(tmp_path / 'node.log'))
    try:
        p = subprocess.run([harness, '_mode:=socket', '_tcp_port:=%d' % port], env=roscore.env,
                           capture_output=True, text=True, timeout=300)
        assert p.returncode == 0 and '[  PASSED  ] 3 tests.' in p.stdout, \
            p.stdout[-3000:] + '\nserial_node.py:\n' + node.output()[-3000:]
    finally:
        node.stop()
