"""A rosserial device in Python on the master side of a real pty, for the host's tests."""
import os
import select
import threading
import time

from rosserial_python import protocol as p

STRING_MD5 = '992ce8a1687cec8c8bd883ec73ca41d1'
EMPTY_MD5 = 'd41d8cd98f00b204e9800998ecf8427e'


class FakeDevice(object):
    """Answers the topic request like ros_lib's NodeHandle: a time request, then one TopicInfo
    per publisher and per subscriber. `announce` is [(endpoint, TopicInfo)]."""

    def __init__(self, announce=(), answer_topic_requests=True):
        self.master, slave = os.openpty()
        self.path = os.ttyname(slave)
        self.slave = slave            # kept open so the pty survives until close()
        import tty
        tty.setraw(self.master)
        self.announce = list(announce)
        self.answer = answer_topic_requests
        self.parser = p.FrameParser()
        self.received = []            # (topic_id, payload) from the host
        self.topic_requests = 0
        self.lock = threading.Lock()
        self._stop = False
        self.thread = threading.Thread(target=self._loop, daemon=True)
        self.thread.start()

    def write(self, data):
        os.write(self.master, data)

    def send(self, topic_id, payload=b''):
        self.write(p.encode_frame(topic_id, payload))

    def negotiate(self):
        self.send(p.ID_TIME, p.encode_time(0, 0))
        for endpoint, info in self.announce:
            self.send(endpoint, info.encode())

    def _loop(self):
        while not self._stop:
            r, _, _ = select.select([self.master], [], [], 0.05)
            if not r:
                continue
            try:
                data = os.read(self.master, 4096)
            except OSError:
                return
            for ev in self.parser.feed(data):
                if ev.kind != 'frame':
                    continue
                with self.lock:
                    self.received.append((ev.topic_id, ev.payload))
                if ev.topic_id == p.ID_PUBLISHER and not ev.payload:
                    self.topic_requests += 1
                    if self.answer:
                        self.negotiate()

    def frames_on(self, topic_id):
        with self.lock:
            return [pl for t, pl in self.received if t == topic_id]

    def wait_for(self, cond, timeout=10.0, what='condition'):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if cond():
                return
            time.sleep(0.01)
        raise AssertionError('timed out after %.0f s waiting for %s' % (timeout, what))

    def close(self):
        self._stop = True
        self.thread.join(2)
        for fd in (self.master, self.slave):
            try:
                os.close(fd)
            except OSError:
                pass
