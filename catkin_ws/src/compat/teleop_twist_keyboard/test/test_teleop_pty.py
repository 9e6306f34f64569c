"""Drive the real teleop_twist_keyboard.py through a pseudo-terminal against a private roscore
and check the Twists that arrive on the (remapped) topic with `rostopic echo -p`."""
import os
import threading
import time

from course_testing import Proc, wait_for

TOPIC = '/teleop_test/cmd_vel'


class Teleop:
    """teleop_twist_keyboard.py on a pty; `.text` is everything it printed so far."""

    def __init__(self, env, *params):
        self.master, slave = os.openpty()
        self.proc = Proc(['rosrun', 'teleop_twist_keyboard', 'teleop_twist_keyboard.py',
                          'cmd_vel:=' + TOPIC] + list(params), env=env, stdin=slave, stdout=slave)
        os.close(slave)
        self._chunks = []
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        while True:
            try:
                data = os.read(self.master, 4096)
            except OSError:
                return
            if not data:
                return
            self._chunks.append(data)

    @property
    def text(self):
        return b''.join(self._chunks).decode('utf-8', 'replace')

    def key(self, k):
        os.write(self.master, k.encode())

    def stop(self):
        code = self.proc.stop()
        os.close(self.master)
        return code


class Echo:
    """`rostopic echo -p TOPIC`: one CSV line per Twist."""

    def __init__(self, env, log):
        self.proc = Proc(['rostopic', 'echo', '-p', TOPIC], env=env, log=log)

    def twists(self):
        """[(receipt time [s], (lin x, y, z, ang x, y, z))] of every message so far."""
        out = []
        for line in self.proc.output().splitlines():
            if line and line[0].isdigit():
                f = line.split(',')
                out.append((int(f[0]) * 1e-9, tuple(float(v) for v in f[1:7])))
        return out

    def wait_count(self, n, timeout=60.0):
        wait_for(lambda: len(self.twists()) >= n, timeout, what='%d twists on %s' % (n, TOPIC))
        return [t for _, t in self.twists()]


def tw(x=0.0, y=0.0, z=0.0, th=0.0):
    return (x, y, z, 0.0, 0.0, th)


def test_keys_speeds_stop_and_ctrl_c(roscore, tmp_path):
    teleop = Teleop(roscore.env)
    echo = None
    try:
        # nobody listens yet: it says so (every 2.5 s) and publishes nothing
        wait_for(lambda: 'Waiting for subscriber to connect to %s' % TOPIC in teleop.text, 60,
                 what='the waiting message')
        assert 'Moving around' not in teleop.text
        echo = Echo(roscore.env, str(tmp_path / 'echo.log'))
        got = echo.wait_count(1, 60)            # first a zero twist, then the help text
        assert got == [tw()]
        wait_for(lambda: 'currently:\tspeed 0.5\tturn 1.0 ' in teleop.text, 60, what='speed line')
        for needle in ('Reading from the keyboard  and Publishing to Twist!', 'u    i    o',
                       'M    <    >', 'q/z : increase/decrease max speeds by 10%', 'CTRL-C to quit'):
            assert needle in teleop.text

        s, t = 0.5, 1.0
        expected = [tw()]
        for key, want in [('i', tw(s)), ('u', tw(s, th=t)), ('o', tw(s, th=-t)), ('j', tw(th=t)),
                          ('l', tw(th=-t)), ('m', tw(-s, th=-t)), (',', tw(-s)), ('.', tw(-s, th=t)),
                          ('U', tw(s, s)), ('I', tw(s)), ('O', tw(s, -s)), ('J', tw(0, s)),
                          ('L', tw(0, -s)), ('M', tw(-s, s)), ('<', tw(-s)), ('>', tw(-s, -s)),
                          ('t', tw(z=s)), ('b', tw(z=-s)), ('k', tw())]:
            teleop.key(key)
            expected.append(want)
            assert echo.wait_count(len(expected)) == expected, 'after key %r' % key

        # speed keys: scale changes, the direction is kept, the status line is printed
        teleop.key('u')
        expected.append(tw(s, th=t))
        assert echo.wait_count(len(expected)) == expected
        for key, (fs, ft) in [('q', (1.1, 1.1)), ('w', (1.1, 1.0)), ('x', (0.9, 1.0)),
                              ('e', (1.0, 1.1)), ('c', (1.0, 0.9)), ('z', (0.9, 0.9))]:
            s, t = s * fs, t * ft
            teleop.key(key)
            expected.append(tw(s, th=t))
            assert echo.wait_count(len(expected)) == expected, 'after key %r' % key
            wait_for(lambda: 'currently:\tspeed %s\tturn %s ' % (s, t) in teleop.text, 60,
                     what='status line after %r' % key)
        teleop.key('a')                          # any other key stops
        expected.append(tw())
        assert echo.wait_count(len(expected)) == expected

        teleop.key('i')
        expected.append(tw(s))
        assert echo.wait_count(len(expected)) == expected
        teleop.key('\x03')                       # Ctrl-C: zero twist, exit 0
        wait_for(lambda: not teleop.proc.alive(), 60, what='teleop to exit on Ctrl-C')
        assert teleop.proc.popen.returncode == 0
        expected.append(tw())
        assert echo.wait_count(len(expected)) == expected
        assert 'Traceback' not in teleop.text
    finally:
        teleop.stop()
        if echo:
            echo.proc.stop()


def test_repeat_rate(roscore, tmp_path):
    echo = Echo(roscore.env, str(tmp_path / 'echo.log'))
    teleop = Teleop(roscore.env, '_repeat_rate:=10.0', '_speed:=0.2', '_turn:=0.3')
    try:
        echo.wait_count(1, 15)
        wait_for(lambda: 'currently:' in teleop.text, 60, what='help text')
        teleop.key('u')
        wait_for(lambda: tw(0.2, th=0.3) in [v for _, v in echo.twists()], 60, what='the first twist')
        time.sleep(2.0)
        moving = [ts for ts, v in echo.twists() if v == tw(0.2, th=0.3)]
        rate = (len(moving) - 1) / (moving[-1] - moving[0])
        assert len(moving) >= 15 and abs(rate - 10.0) < 1.5, (len(moving), rate)
    finally:
        teleop.stop()
        echo.proc.stop()


def test_key_timeout_stops(roscore, tmp_path):
    echo = Echo(roscore.env, str(tmp_path / 'echo.log'))
    teleop = Teleop(roscore.env, '_key_timeout:=0.6')
    try:
        echo.wait_count(1, 15)
        wait_for(lambda: 'currently:' in teleop.text, 60, what='help text')
        teleop.key('i')
        got = echo.wait_count(3, 5)
        assert got == [tw(), tw(0.5), tw()]
        (t_go, _), (t_stop, _) = echo.twists()[1:3]
        assert 0.5 <= t_stop - t_go <= 1.0, t_stop - t_go
        time.sleep(1.5)                           # already stopped: timeouts send nothing more
        assert len(echo.twists()) == 3
        assert teleop.proc.alive()
    finally:
        teleop.stop()
        echo.proc.stop()


def test_stdin_not_a_terminal(roscore):
    import subprocess
    out = subprocess.run(['rosrun', 'teleop_twist_keyboard', 'teleop_twist_keyboard.py'],
                         env=roscore.env, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                         timeout=30)
    assert out.returncode == 1
    assert out.stderr.strip().startswith('teleop_twist_keyboard: standard input is not a terminal')
    assert 'Traceback' not in out.stderr


def test_sigint_stops_with_zero_twist(roscore, tmp_path):
    # e.g. roslaunch stopping the node: it leaves promptly and sends the zero twist
    echo = Echo(roscore.env, str(tmp_path / 'echo.log'))
    teleop = Teleop(roscore.env)
    try:
        echo.wait_count(1, 15)
        wait_for(lambda: 'currently:' in teleop.text, 60, what='help text')
        teleop.key('j')
        assert echo.wait_count(2) == [tw(), tw(th=1.0)]
        os.killpg(teleop.proc.pid, 2)
        wait_for(lambda: not teleop.proc.alive(), 60, what='teleop to exit on SIGINT')
        assert echo.wait_count(3) == [tw(), tw(th=1.0), tw()]
        assert 'Traceback' not in teleop.text, teleop.text
    finally:
        teleop.stop()
        echo.proc.stop()
