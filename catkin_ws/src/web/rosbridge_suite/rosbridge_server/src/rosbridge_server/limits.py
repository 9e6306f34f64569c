"""Per-client budgets and the server's limit counters (no ROS, no tornado)."""
import threading
import time


class Budget(object):
    """A token bucket: `rate` units a second, at most `capacity` saved up. take(n) is False
    when the client has spent more than that (it is then cut off)."""

    def __init__(self, rate, capacity, clock=time.monotonic):
        if rate <= 0 or capacity <= 0:
            raise ValueError('rate and capacity must be positive')
        self.rate = float(rate)
        self.capacity = float(capacity)
        self.clock = clock
        self.level = self.capacity
        self.last = clock()

    def take(self, amount=1.0):
        now = self.clock()
        self.level = min(self.capacity, self.level + (now - self.last) * self.rate)
        self.last = now
        self.level -= amount
        return self.level >= 0


class Counters(object):
    """How often each limit was hit, for the whole server (thread-safe)."""
    NAMES = ('messages_too_large', 'queue_dropped', 'subscriptions_refused',
             'connections_refused', 'clients_cut_off', 'auth_refused')

    def __init__(self, on_change=None):
        self.lock = threading.Lock()
        self.values = dict.fromkeys(self.NAMES, 0)
        self.on_change = on_change or (lambda values: None)

    def add(self, name, n=1):
        if n <= 0:
            return
        with self.lock:
            self.values[name] = self.values.get(name, 0) + n
            values = dict(self.values)
        self.on_change(values)

    def snapshot(self):
        with self.lock:
            return dict(self.values)
