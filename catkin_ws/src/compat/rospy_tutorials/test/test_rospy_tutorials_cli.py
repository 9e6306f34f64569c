"""The rospy_tutorials command lines as a student types them, against a private roscore."""
import re
import subprocess

import pytest
from course_testing import Proc, wait_for


MD5 = {
    ('rosmsg', 'rospy_tutorials/Floats'): '420cd38b6b071cd49f2970c3e2cee511',
    ('rosmsg', 'rospy_tutorials/HeaderString'): 'c99a9440709e4d4a9716d55b8270d5e7',
    ('rossrv', 'rospy_tutorials/AddTwoInts'): '6a2e34150c00229791cc89ff309fff21',
}


@pytest.mark.parametrize('tool,type_name', sorted(MD5))
def test_md5_matches_original(tool, type_name):
    out = subprocess.run([tool, 'md5', type_name], capture_output=True, text=True, timeout=30)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == MD5[(tool, type_name)]


def test_generated_classes_match_original():
    from rospy_tutorials.msg import Floats, HeaderString
    from rospy_tutorials.srv import (AddTwoInts, AddTwoIntsRequest, AddTwoIntsResponse,
                                     BadTwoInts, BadTwoIntsRequest, BadTwoIntsResponse)
    assert AddTwoIntsRequest._md5sum == '36d09b846be0b371c5f190354dd3153e'
    assert AddTwoIntsResponse._md5sum == 'b88405221c77b1878a3cbbfff53428d7'
    assert AddTwoInts._md5sum == '6a2e34150c00229791cc89ff309fff21'
    assert (AddTwoIntsRequest.__slots__, AddTwoIntsRequest._slot_types) == (['a', 'b'], ['int64', 'int64'])
    assert (BadTwoIntsRequest.__slots__, BadTwoIntsRequest._slot_types) == (['a', 'b'], ['int64', 'int32'])
    assert (BadTwoIntsResponse.__slots__, BadTwoIntsResponse._slot_types) == (['sum'], ['int32'])
    assert BadTwoInts._md5sum != AddTwoInts._md5sum
    assert (Floats.__slots__, Floats._slot_types) == (['data'], ['float32[]'])
    assert (HeaderString.__slots__, HeaderString._slot_types) == (['header', 'data'], ['std_msgs/Header', 'string'])


def _run(cmd, env, timeout=120):
    # the timeout only bounds a hung command: under full load, rosrun + a rospy start-up took
    # over 20 s (make test-stress) for what takes 1.2 s on a quiet machine
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)


def test_talker_listener_and_rate(roscore, tmp_path):
    talker = Proc(['rosrun', 'rospy_tutorials', 'talker'], env=roscore.env, log=str(tmp_path / 'talker.log'))
    listener = Proc(['rosrun', 'rospy_tutorials', 'listener'], env=roscore.env,
                    log=str(tmp_path / 'listener.log'))
    try:
        heard = re.compile(r'\[INFO\] \[[\d.]+\]: /listener_\d+_\d+I heard hello world \d+\.\d+')
        wait_for(lambda: heard.search(listener.output()), 30, what='the listener to print "I heard ..."')
        assert re.search(r'\[INFO\] \[[\d.]+\]: hello world \d+\.\d+', talker.output())
        # both nodes are anonymous
        nodes = _run(['rosnode', 'list'], roscore.env).stdout.split()
        assert any(re.fullmatch(r'/talker_\d+_\d+', n) for n in nodes), nodes
        assert any(re.fullmatch(r'/listener_\d+_\d+', n) for n in nodes), nodes
        # `rostopic hz` reports ~10 Hz
        hz = Proc(['rostopic', 'hz', '/chatter'], env=roscore.env, log=str(tmp_path / 'hz.log'))
        try:
            def rates():
                return re.findall(r'average rate: ([\d.]+)', hz.output())
            wait_for(lambda: len(rates()) >= 3, 30, what='three `rostopic hz` reports')
        finally:
            hz.stop()
        assert abs(float(rates()[-1]) - 10.0) < 0.5, hz.output()
        # `rostopic echo -n 1` shows the text
        echo = _run(['rostopic', 'echo', '-n', '1', '/chatter'], roscore.env)
        assert re.search(r'^data: "hello world \d+\.\d+"', echo.stdout, re.M), echo.stdout
    finally:
        talker.stop()
        listener.stop()


def test_add_two_ints_cli(roscore, tmp_path):
    server = Proc(['rosrun', 'rospy_tutorials', 'add_two_ints_server'], env=roscore.env,
                  log=str(tmp_path / 'server.log'))
    try:
        out = _run(['rosrun', 'rospy_tutorials', 'add_two_ints_client', '3', '4'], roscore.env)
        assert out.returncode == 0, out.stdout + out.stderr
        assert out.stdout.splitlines() == ['Requesting 3+4', '3 + 4 = 7']
        # the server prints each request (the client calls twice: positional and request object)
        wait_for(lambda: server.output().count('Returning [3 + 4 = 7]') == 2, 10, what='server output')
        assert 'Ready to add two ints.' in server.output()

        out = _run(['rosservice', 'call', '/add_two_ints', '3', '4'], roscore.env)
        assert out.returncode == 0, out.stderr
        assert out.stdout.strip() == 'sum: 7'
        assert _run(['rosservice', 'type', '/add_two_ints'], roscore.env).stdout.strip() == \
            'rospy_tutorials/AddTwoInts'
        assert '/add_two_ints_server' in _run(['rosnode', 'list'], roscore.env).stdout.split()

        out = _run(['rosrun', 'rospy_tutorials', 'add_two_ints_client'], roscore.env)
        assert out.returncode == 0, out.stdout + out.stderr
        m = re.fullmatch(r'Requesting (-?\d+)\+(-?\d+)\n(-?\d+) \+ (-?\d+) = (-?\d+)\n', out.stdout)
        assert m, out.stdout
        x, y = int(m.group(1)), int(m.group(2))
        assert -50000 <= x <= 50000 and -50000 <= y <= 50000
        assert (int(m.group(3)), int(m.group(4)), int(m.group(5))) == (x, y, x + y)
    finally:
        server.stop()


@pytest.mark.parametrize('args', [['3'], ['a', 'b'], ['1', '2', '3'], ['1.5', '2']])
def test_add_two_ints_client_bad_args(args):
    # no master needed: arguments are checked first, so nothing hangs
    out = _run(['rosrun', 'rospy_tutorials', 'add_two_ints_client'] + args,
               dict(__import__('os').environ, ROS_MASTER_URI='http://127.0.0.1:9'))
    assert out.returncode == 1
    assert out.stdout.startswith('usage: add_two_ints_client [x y]')
    assert len(out.stdout.splitlines()) == 1
    assert 'Traceback' not in out.stderr


def test_client_waits_for_server(roscore, tmp_path):
    client = Proc(['rosrun', 'rospy_tutorials', 'add_two_ints_client', '10', '-3'], env=roscore.env,
                  log=str(tmp_path / 'client.log'))
    server = None
    try:
        wait_for(lambda: 'Waiting for service add_two_ints' in client.output(), 15, what='waiting notice')
        assert client.alive()
        server = Proc(['rosrun', 'rospy_tutorials', 'add_two_ints_server'], env=roscore.env)
        wait_for(lambda: not client.alive(), 20, what='the client to finish')
        assert client.popen.returncode == 0
        assert '10 + -3 = 7' in client.output()
    finally:
        client.stop()
        if server:
            server.stop()
