"""rosio.FanoutPublisher (/clock): a publish hands its frame to the compiled core's sending
thread once for all subscribers; every socket gets it whole; a full socket misses it whole
without blocking the publisher; a connection rospy drops stops getting frames; a failed
socket ends its connection as rospy's own write does; a connection without a socket keeps
rospy's queue. No master: rospy's QueuedConnection over socket pairs or a stand-in transport."""
import socket

import pytest
from rospy.exceptions import TransportTerminated
from rospy.impl.tcpros_pubsub import QueuedConnection

from ode_sim.engine._core import Fanout
from ode_sim.ros.plugins.rosio import FanoutPublisher, _FanoutWrite, _NoYieldWrite, _direct, _queued


class _Transport:
    """The TCPROS transport under a QueuedConnection: `done` at first, so that the queue's
    sender thread exits at once and the queue stays as written; then live."""

    def __init__(self, sock):
        self.socket = sock
        self.done = True
        self.closed = False
        self.stat_bytes = self.stat_num_msg = 0

    def set_cleanup_callback(self, cb):
        self.cb = cb

    def close(self):
        self.closed = True
        self.done = True


def connection(sock):
    t = _Transport(sock)
    c = QueuedConnection(t, 10)
    c._thread.join(5)
    t.done = False
    assert _queued(c) and _direct(c)
    return c, t


class _Publisher:
    """FanoutPublisher's own state and methods, without rospy's topic registration."""
    _sync = FanoutPublisher._sync

    def __init__(self):
        self._fan = Fanout()
        self._handles, self._dead, self._seen, self.handed = {}, set(), None, None

    def publish(self, conns, data):
        """What FanoutPublisher.publish does around rospy's write loop."""
        if conns is not self._seen:
            self._sync(conns)
        self._dead.update(self._fan.take_dead())
        data = bytes(bytearray(data))           # a new object per publish, as rospy's buffer
        for c in conns:
            c.write_data(data)
        self._fan.flush()


@pytest.fixture
def pub():
    p = _Publisher()
    yield p
    p._fan.close()


@pytest.fixture
def pairs():
    made = []

    def make():
        a, b = socket.socketpair()
        made.extend((a, b))
        return a, b
    yield make
    for s in made:
        s.close()


def test_one_hand_over_per_publish_and_every_socket_gets_the_frame(pub, pairs):
    ends = [pairs() for _ in range(3)]
    conns = [connection(a)[0] for a, _ in ends]
    pub.publish(conns, b'clock-1')
    pub.publish(conns, b'clock-2')
    assert all(isinstance(c.write_data, _FanoutWrite) for c in conns)
    assert len(pub._fan) == 3 and pub._fan.sent == 6
    for _, b in ends:
        assert b.recv(100) == b'clock-1clock-2'
    assert all((c._connection.stat_bytes, c._connection.stat_num_msg) == (14, 2) for c in conns)
    assert all(c._queue == [] for c in conns)       # nothing through rospy's queue


def test_a_full_socket_misses_a_frame_whole_and_the_publisher_does_not_wait(pub, pairs):
    (a, b), (a2, b2) = pairs(), pairs()
    conns = [connection(a)[0], connection(a2)[0]]
    a.setblocking(False)
    filled = 0
    for chunk in (4096, 1):
        try:
            while True:
                filled += a.send(b'f' * chunk)
        except BlockingIOError:
            pass
    pub.publish(conns, b'x' * 16)
    assert pub._fan.dropped == 1 and b2.recv(100) == b'x' * 16
    b.setblocking(False)
    got = b''
    try:
        while True:
            got += b.recv(65536)
    except BlockingIOError:
        pass
    assert len(got) == filled and b'x' not in got
    pub.publish(conns, b'y' * 16)                    # reading again: whole frames again
    assert b.recv(100) == b'y' * 16


def test_a_connection_rospy_drops_gets_no_more_frames(pub, pairs):
    (a, b), (a2, b2) = pairs(), pairs()
    (c1, _), (c2, _) = connection(a), connection(a2)
    pub.publish([c1, c2], b'one')
    pub.publish([c2], b'two')                        # rospy replaced the list without c1
    assert len(pub._fan) == 1 and c1 not in pub._handles
    a.close()                                        # rospy closes its socket: the end
    assert b.recv(100) == b'one' and b.recv(100) == b''
    assert b2.recv(100) == b'onetwo'


def test_a_failed_socket_ends_the_connection(pub, pairs):
    (a, b), (a2, b2) = pairs(), pairs()
    (c1, t1), (c2, t2) = connection(a), connection(a2)
    b.close()                                        # the subscriber is gone
    pub.publish([c1, c2], b'one')
    pub._dead.update(pub._fan.take_dead())
    with pytest.raises(TransportTerminated):         # rospy then drops the connection
        c1.write_data(b'two')
    assert t1.closed and not t2.closed
    assert c2.write_data(b'two') is True
    pub._fan.flush()
    assert b2.recv(100) == b'onetwo'


class _NoSocket:
    """A transport without a socket (not TCPROS over a socket)."""
    socket = None
    done = True
    stat_bytes = stat_num_msg = 0

    def set_cleanup_callback(self, cb):
        pass

    def close(self):
        self.done = True


def test_a_connection_without_a_socket_keeps_the_queue(pub):
    t = _NoSocket()
    c = QueuedConnection(t, 10)
    c._thread.join(5)
    t.done = False
    pub._sync([c])
    assert isinstance(c.write_data, _NoYieldWrite) and len(pub._fan) == 0
    assert c.write_data(b'abc') is True and c._queue == [b'abc']
