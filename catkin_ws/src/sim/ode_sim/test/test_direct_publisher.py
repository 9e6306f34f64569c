"""rosio.DirectPublisher's write (/clock): the message goes to the subscriber's socket from the
publishing thread; a full socket drops that message; a partial send hands the rest, and every
later message, to rospy's queue (framing kept); a broken socket ends the connection as rospy's
own write does. No master: rospy's QueuedConnection over a socketpair or a stand-in socket."""
import socket

import pytest
from rospy.exceptions import TransportTerminated
from rospy.impl.tcpros_pubsub import QueuedConnection

from ode_sim.ros.plugins.rosio import _direct, _DirectWrite, _queued


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


def test_sends_from_the_calling_thread_and_drops_when_the_socket_is_full():
    a, b = socket.socketpair()
    try:
        c, t = connection(a)
        write = _DirectWrite(c)
        assert write(b'clock-1') is True and write(b'clock-2') is True
        assert b.recv(100) == b'clock-1clock-2'
        assert (t.stat_bytes, t.stat_num_msg) == (14, 2) and c._queue == []
        # fill the socket (the subscriber reads nothing): the next message is dropped whole
        a.setblocking(False)
        filled = 0
        try:
            while True:
                filled += a.send(b'f' * 4096)
        except BlockingIOError:
            pass
        a.setblocking(True)
        assert write(b'x' * 16) is True and c._queue == []
        got = 0
        b.setblocking(False)
        try:
            while True:
                chunk = b.recv(65536)
                assert b'x' not in chunk
                got += len(chunk)
        except BlockingIOError:
            pass
        assert got == filled
    finally:
        a.close()
        b.close()


class _PartialSocket:
    def __init__(self, take):
        self.take, self.sent = take, []

    def send(self, data, flags=0):
        self.sent.append(bytes(data[:self.take]))
        return min(self.take, len(data))


def test_a_partial_send_leaves_the_rest_and_later_messages_to_the_queue():
    sock = _PartialSocket(3)
    c, t = connection(sock)
    write = _DirectWrite(c)
    assert write(b'abcdef') is True
    assert sock.sent == [b'abc'] and c._queue == [b'def']
    assert write(b'ghi') is True            # in order, after the rest of the first
    assert sock.sent == [b'abc'] and c._queue == [b'def', b'ghi']


class _BrokenSocket:
    def send(self, data, flags=0):
        raise ConnectionResetError(104, 'Connection reset by peer')


def test_a_broken_socket_ends_the_connection():
    c, t = connection(_BrokenSocket())
    write = _DirectWrite(c)
    with pytest.raises(TransportTerminated):
        write(b'abc')
    assert t.closed
    with pytest.raises(TransportTerminated):    # closed: rospy drops the connection
        write(b'abc')
