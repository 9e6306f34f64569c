"""serial_node.py against a fake device on a pty with a private roscore: a device publisher
reaches ROS, a ROS message reaches the device subscriber, parameters are answered relative to
the node, the device's log lands in rosout, and the node reconnects after the port vanishes."""
import os
import subprocess
import sys
import time

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fake_device import EMPTY_MD5, STRING_MD5, FakeDevice  # noqa: E402

from course_testing import Proc, wait_for  # noqa: E402
from rosserial_python import protocol as p  # noqa: E402

ANNOUNCE = [(p.ID_PUBLISHER, p.TopicInfo(125, 'chatter', 'std_msgs/String', STRING_MD5, 512)),
            (p.ID_SUBSCRIBER, p.TopicInfo(100, 'toggle_led', 'std_msgs/Empty', EMPTY_MD5, 512))]


@pytest.mark.full   # ~20-50 s; the gate runs serial_node against the emulated Mega instead
def test_serial_node_bridges_a_pty_device(roscore, tmp_path):
    dev = FakeDevice(ANNOUNCE)
    log = str(tmp_path / 'serial_node.log')
    node = Proc(['rosrun', 'rosserial_python', 'serial_node.py', dev.path, '_gain:=2.5'],
                env=roscore.env, log=log)
    echo = None
    try:
        wait_for(lambda: 'Setup subscriber on toggle_led' in node.output(), 30,
                 what='negotiation (serial_node log):\n' + node.output())
        out = node.output()
        for line in ('ROS Serial Python Node', 'Connecting to %s at 57600 baud' % dev.path,
                     'Requesting topics...', 'Setup publisher on chatter [std_msgs/String]',
                     'Note: publish buffer size is 512 bytes'):
            assert line in out, line
        echo = subprocess.Popen(['rostopic', 'echo', '-n', '1', '/chatter'], env=roscore.env,
                                stdout=subprocess.PIPE, text=True, start_new_session=True)
        deadline = time.monotonic() + 30
        while echo.poll() is None and time.monotonic() < deadline:
            dev.send(125, p.pack_string('hello world!'))
            time.sleep(0.2)
        assert echo.poll() == 0, 'no /chatter message from the device within 30 s'
        assert 'data: "hello world!"' in echo.stdout.read()

        subprocess.run(['rostopic', 'pub', '-1', '/toggle_led', 'std_msgs/Empty'],
                       env=roscore.env, timeout=60, check=True, capture_output=True)
        dev.wait_for(lambda: dev.frames_on(100), 20, 'toggle_led frame on the device')

        dev.send(p.ID_PARAMETER_REQUEST, p.encode_param_request('~gain'))
        dev.wait_for(lambda: dev.frames_on(p.ID_PARAMETER_REQUEST), 20, 'param reply')
        assert p.decode_param_response(dev.frames_on(p.ID_PARAMETER_REQUEST)[0]) == \
            ([], [2.5], [])
        dev.send(p.ID_LOG, p.encode_log(2, 'battery low'))
        wait_for(lambda: 'battery low' in node.output(), 20, what='device log in the node log')

        # the port vanishes: the node keeps trying to reopen it, with the original's message
        dev.close()
        wait_for(lambda: 'Error opening serial' in node.output(), 30,
                 what='"Error opening serial" after the pty vanished:\n' + node.output()[-2000:])
        assert node.alive()
    finally:
        if echo is not None and echo.poll() is None:
            echo.kill()
            echo.wait()
        node.stop()
        dev.close()


def test_a_message_published_once_right_after_sync_reaches_every_subscriber(roscore, tmp_path):
    """The device publishes a single message as soon as its publisher is set up: a subscriber
    waiting before the node started and one that subscribes afterwards both receive it."""
    early = subprocess.Popen(['rostopic', 'echo', '-n', '1', '/status'], env=roscore.env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             start_new_session=True)
    dev = FakeDevice([(p.ID_PUBLISHER, p.TopicInfo(125, 'status', 'std_msgs/String',
                                                   STRING_MD5, 512))])
    node = Proc(['rosrun', 'rosserial_python', 'serial_node.py', dev.path],
                env=roscore.env, log=str(tmp_path / 'serial_node.log'))
    late = None
    try:
        wait_for(lambda: 'Setup publisher on status' in node.output(), 60,
                 what='negotiation (serial_node log):\n' + node.output())
        dev.send(125, p.pack_string('booted'))
        out, _ = early.communicate(timeout=60)
        assert 'data: "booted"' in out, out
        late = subprocess.run(['rostopic', 'echo', '-n', '1', '/status'], env=roscore.env,
                              capture_output=True, text=True, timeout=60)
        assert 'data: "booted"' in late.stdout, late.stdout + late.stderr
        assert node.alive()
    finally:
        if early.poll() is None:
            early.kill()
            early.wait()
        node.stop()
        dev.close()
