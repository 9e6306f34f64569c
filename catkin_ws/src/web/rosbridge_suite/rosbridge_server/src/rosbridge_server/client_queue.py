"""A client's bounded outgoing queue (no ROS, no tornado).

Producers (ROS callback threads, service threads, the IO loop) `put` frames; the client's
writer on the IO loop `get`s them one at a time and waits for each write to reach the socket
before taking the next. A client that does not read fills only its own queue: past
`max_messages` frames or `max_bytes` bytes the oldest frames are dropped and counted, so the
publishers and the other clients never wait for it and the server's memory stays bounded.
"""
import collections
import threading


class ClientQueue(object):
    def __init__(self, max_messages=1000, max_bytes=32 * 1024 * 1024):
        if max_messages < 1 or max_bytes < 1:
            raise ValueError('max_messages and max_bytes must be positive')
        self.max_messages = max_messages
        self.max_bytes = max_bytes
        self.lock = threading.Lock()
        self.items = collections.deque()
        self.bytes = 0
        self.dropped = 0
        self.sent = 0
        self.high_water = 0        # most bytes ever queued at once
        self.busy = False          # a writer is draining the queue
        self.closed = False

    def put(self, data, binary=False):
        """Queue a frame; True if the writer is idle and must be started."""
        with self.lock:
            if self.closed:
                return False
            self.items.append((data, binary))
            self.bytes += len(data)
            while len(self.items) > self.max_messages or (
                    self.bytes > self.max_bytes and len(self.items) > 1):
                old, _ = self.items.popleft()
                self.bytes -= len(old)
                self.dropped += 1
            self.high_water = max(self.high_water, self.bytes)
            if self.busy:
                return False
            self.busy = True
            return True

    def get(self):
        """The next frame (data, binary), or None: then the writer stops and is idle."""
        with self.lock:
            if self.items and not self.closed:
                data, binary = self.items.popleft()
                self.bytes -= len(data)
                self.sent += 1
                return data, binary
            self.busy = False
            return None

    def close(self):
        with self.lock:
            self.closed = True
            self.items.clear()
            self.bytes = 0

    def __len__(self):
        with self.lock:
            return len(self.items)
