"""turtle_teleop_key on a real pseudo-terminal: arrow keys -> Twists -> the turtle moves; q quits."""
import os
import pty
import select
import subprocess
import time

import pytest

from course_testing import Proc, wait_for

CENTRE = 499.0 / 45.0 / 2.0


def headless(env):
    env = dict(env)
    env.pop('DISPLAY', None)
    return env


def pose(env):
    out = subprocess.run(['rostopic', 'echo', '-n', '1', '/turtle1/pose'], env=env,
                         capture_output=True, text=True, timeout=15).stdout
    fields = dict(line.split(': ') for line in out.splitlines() if ': ' in line)
    return {k: float(v) for k, v in fields.items()}


def connected(env, node, topic, peers):
    out = subprocess.run(['rosnode', 'info', node], env=env, capture_output=True, text=True,
                         timeout=15).stdout
    block = out.split('topic: ' + topic)[1:] if topic in out else []
    text = ''.join(block)
    return all(('to: ' + p) in text for p in peers)


def twists(log):
    """linear.x, angular.z of each Twist in a `rostopic echo -p` log."""
    lines = open(log).read().split('\n')[:-1]          # complete lines only
    rows = [l.split(',') for l in lines if l[:1].isdigit()]
    return [(float(r[1]), float(r[6])) for r in rows if len(r) == 7]


def read_until(fd, text, timeout=10.0):
    buf = b''
    deadline = time.monotonic() + timeout
    while text.encode() not in buf:
        left = deadline - time.monotonic()
        if left <= 0:
            raise AssertionError('no %r on the terminal; got %r' % (text, buf))
        if select.select([fd], [], [], left)[0]:
            buf += os.read(fd, 1024)
    return buf.decode()


def test_teleop_keys_drive_turtle(roscore, tmp_path):
    env = headless(roscore.env)
    subprocess.run(['rosparam', 'set', '/scale_angular', '1.5'], env=env, check=True, timeout=120)
    sim = Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=env, log=str(tmp_path / 'sim.log'))
    echo_log = str(tmp_path / 'cmd_vel.csv')
    echo = Proc(['rostopic', 'echo', '-p', '/turtle1/cmd_vel'], env=env, log=echo_log)
    master, slave = pty.openpty()
    teleop = subprocess.Popen(['rosrun', 'turtlesim', 'turtle_teleop_key'], env=env, stdin=slave,
                              stdout=slave, stderr=slave, start_new_session=True)
    os.close(slave)
    try:
        banner = read_until(master, "'q' to quit.")
        assert 'Reading from keyboard' in banner
        assert '---------------------------' in banner
        assert "Use arrow keys to move the turtle. 'q' to quit." in banner
        wait_for(lambda: connected(env, '/teleop_turtle', '/turtle1/cmd_vel',
                                   ['/turtlesim', '/rostopic']), 30, 0.3, 'teleop connections')
        start = pose(env)
        assert start['x'] == pytest.approx(CENTRE, abs=1e-5)

        os.write(master, b'\x1b[A')                      # up arrow
        wait_for(lambda: twists(echo_log), 60, 0.1, 'a Twist from the up arrow')
        moved = wait_for(lambda: (lambda p: p if p['linear_velocity'] == 0.0
                                  and p['x'] > CENTRE + 1.5 else None)(pose(env)),
                         10, 0.1, 'the turtle to move ~2 m and stop')
        assert moved['x'] - CENTRE == pytest.approx(2.0, abs=0.15)   # 2 m/s for ~1 s
        assert moved['y'] == pytest.approx(CENTRE, abs=1e-5)

        os.write(master, b'\x1b[D')                      # left arrow: turn
        wait_for(lambda: len(twists(echo_log)) >= 2, 60, 0.1, 'a Twist from the left arrow')
        turned = wait_for(lambda: (lambda p: p if p['angular_velocity'] == 0.0
                                   and p['theta'] > 1.0 else None)(pose(env)),
                          10, 0.1, 'the turtle to turn ~1.5 rad')
        assert turned['theta'] == pytest.approx(1.5, abs=0.1)

        os.write(master, b'x')                           # not a key: nothing published
        os.write(master, b'q')
        assert teleop.wait(10) == 0
        time.sleep(0.5)
        assert twists(echo_log) == [(2.0, 0.0), (0.0, 1.5)]
    finally:
        if teleop.poll() is None:
            os.killpg(teleop.pid, 9)
            teleop.wait()
        os.close(master)
        echo.stop()
        sim.stop()


def test_teleop_without_terminal_fails_clearly(roscore):
    r = subprocess.run(['rosrun', 'turtlesim', 'turtle_teleop_key'], env=headless(roscore.env),
                       stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=30)
    assert r.returncode == 1
    assert r.stderr.strip().splitlines() == [
        'turtle_teleop_key: standard input is not a terminal; run it in a terminal window']
