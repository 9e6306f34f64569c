"""Unit tests of the key maps, the command state and the publishing thread (no roscore)."""
import time

import numpy as np

from twist_keyboard.bindings import (HELP, MOVE_BINDINGS, SPEED_BINDINGS, TeleopState, vels)
from twist_keyboard.publish_thread import PublishThread, make_twist


def test_move_bindings_are_the_originals():
    assert MOVE_BINDINGS == {
        'u': (1, 0, 0, 1), 'i': (1, 0, 0, 0), 'o': (1, 0, 0, -1),
        'j': (0, 0, 0, 1), 'l': (0, 0, 0, -1),
        'm': (-1, 0, 0, -1), ',': (-1, 0, 0, 0), '.': (-1, 0, 0, 1),
        'U': (1, 1, 0, 0), 'I': (1, 0, 0, 0), 'O': (1, -1, 0, 0),
        'J': (0, 1, 0, 0), 'L': (0, -1, 0, 0),
        'M': (-1, 1, 0, 0), '<': (-1, 0, 0, 0), '>': (-1, -1, 0, 0),
        't': (0, 0, 1, 0), 'b': (0, 0, -1, 0)}
    assert SPEED_BINDINGS == {'q': (1.1, 1.1), 'z': (0.9, 0.9), 'w': (1.1, 1.0),
                              'x': (0.9, 1.0), 'e': (1.0, 1.1), 'c': (1.0, 0.9)}
    assert 'k' not in MOVE_BINDINGS


def test_vels_line():
    assert vels(0.5, 1.0) == 'currently:\tspeed 0.5\tturn 1.0 '


def test_move_keys_scale_by_speed_and_turn():
    s = TeleopState(speed=0.5, turn=1.0)
    assert s.command() == (0.0, 0.0, 0.0, 0.0)
    assert s.handle('u') == (True, [])
    assert s.command() == (0.5, 0.0, 0.0, 1.0)
    s.handle('>')
    assert s.command() == (-0.5, -0.5, 0.0, 0.0)
    s.handle('t')
    assert s.command() == (0.0, 0.0, 0.5, 0.0)
    s.handle('.')
    assert s.command() == (-0.5, 0.0, 0.0, 1.0)


def test_speed_keys_change_scale_and_keep_direction():
    s = TeleopState(speed=0.5, turn=1.0)
    s.handle('u')
    publish, lines = s.handle('q')
    assert publish and lines == [vels(0.5 * 1.1, 1.0 * 1.1)]
    assert s.command() == (0.5 * 1.1, 0.0, 0.0, 1.0 * 1.1)
    s.handle('x')
    assert (s.speed, s.turn) == (0.5 * 1.1 * 0.9, 1.0 * 1.1)
    s.handle('c')
    assert (s.speed, s.turn) == (0.5 * 1.1 * 0.9, 1.0 * 1.1 * 0.9)


def test_help_reprinted_every_15th_speed_change():
    s = TeleopState()
    with_help = [i for i in range(45) if HELP in s.handle('w')[1]]
    assert with_help == [14, 29, 44]


def test_other_keys_stop_and_timeout_when_stopped_sends_nothing():
    s = TeleopState()
    s.handle('i')
    assert s.handle('k') == (True, [])
    assert s.command() == (0.0, 0.0, 0.0, 0.0)
    assert s.handle('') == (False, [])       # key timeout while stopped: nothing
    s.handle('j')
    assert s.handle('') == (True, [])        # key timeout while moving: stop
    assert s.command() == (0.0, 0.0, 0.0, 0.0)
    s.handle('i')
    assert s.handle('\x03') == (False, [])   # Ctrl-C: quit (the thread sends the zero twist)
    assert s.quit and s.stopped()


class FakePublisher:
    def __init__(self, connections=1):
        self.msgs = []
        self.times = []
        self.connections = connections

    def publish(self, msg):
        self.msgs.append(msg)
        self.times.append(time.monotonic())

    def get_num_connections(self):
        return self.connections


def twist_tuple(t):
    return (t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z)


def _wait(cond, timeout=30.0):
    deadline = time.monotonic() + timeout
    while not cond():
        assert time.monotonic() < deadline, 'timed out'
        time.sleep(0.005)


def test_thread_publishes_on_update_only_and_zero_at_stop():
    pub = FakePublisher()
    th = PublishThread(pub, 0.0)
    th.update(0.5, 0.0, 0.0, 1.0)
    _wait(lambda: len(pub.msgs) == 1)
    time.sleep(0.3)
    assert len(pub.msgs) == 1
    th.stop()
    assert [twist_tuple(m) for m in pub.msgs] == [(0.5, 0, 0, 0, 0, 1.0), (0, 0, 0, 0, 0, 0)]
    assert not th.is_alive()


def test_thread_repeats_at_rate():
    """At repeat_rate 20 the last command is published again and again, never faster than the
    rate (a loaded machine may only make it slower: no upper bound on the intervals)."""
    pub = FakePublisher()
    th = PublishThread(pub, 20.0)
    th.update(1.0, 0.0, 0.0, 0.0)
    _wait(lambda: len(pub.msgs) >= 12)
    th.stop()
    gaps = np.diff(pub.times[:-1])
    assert len(gaps) >= 11 and np.median(gaps) >= 0.045, gaps
    assert all(twist_tuple(m) == (1.0, 0, 0, 0, 0, 0) for m in pub.msgs[:-1])
    assert twist_tuple(pub.msgs[-1]) == (0, 0, 0, 0, 0, 0)


def test_wait_for_subscribers_says_it_is_waiting():
    pub = FakePublisher(connections=0)
    th = PublishThread(pub)
    said = []
    slept = []

    def sleep(dt):
        slept.append(dt)
        if len(slept) == 12:
            pub.connections = 1
    assert th.wait_for_subscribers(lambda: False, sleep, said.append, '/cmd_vel')
    assert said == ['Waiting for subscriber to connect to /cmd_vel'] * 2   # every 2.5 s
    assert th.wait_for_subscribers(lambda: True, sleep, said.append) is False
    th.stop()


def test_make_twist():
    assert twist_tuple(make_twist(1, 2, 3, 4)) == (1, 2, 3, 0, 0, 4)


def test_a_key_typed_between_reads_is_not_lost():
    """A key that arrives while the terminal is back in normal mode (between two reads, while
    the node prints) is the next key read; raw mode that flushed pending input lost it."""
    import os
    from twist_keyboard.terminal import KeyReader
    master, slave = os.openpty()
    try:
        reader = KeyReader(slave)
        os.write(master, b'i')
        assert reader.get_key(timeout=0.5) == 'i'
        os.write(master, b'u')                  # typed after that read restored normal mode
        assert reader.get_key(timeout=0.5) == 'u'
        assert reader.get_key(timeout=0.2) == ''
    finally:
        os.close(master)
        os.close(slave)
