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

    def _refill(self):
        now = self.clock()
        self.level = min(self.capacity, self.level + (now - self.last) * self.rate)
        self.last = now

    def take(self, amount=1.0):
        self._refill()
        self.level = max(-self.capacity, self.level - amount)
        return self.level >= 0

    def penalize(self):
        """Empty and more: nothing passes for capacity / rate seconds."""
        self._refill()
        self.level = -self.capacity

    def full(self):
        self._refill()
        return self.level >= self.capacity


class AddressBudgets(object):
    """The incoming budgets of one client address, shared by all its connections: a client
    that is cut off and reconnects finds its budget spent."""

    def __init__(self, bytes_per_second, messages_per_second, errors_per_second,
                 clock=time.monotonic):
        self.bytes = Budget(bytes_per_second, 2 * bytes_per_second, clock)
        self.messages = Budget(messages_per_second, 2 * messages_per_second, clock)
        self.errors = Budget(errors_per_second, 10 * errors_per_second, clock)
        self.clock = clock
        self.last_log = None
        self.unlogged = 0

    def should_log(self, every=5.0):
        """At most one cut-off line per `every` s for an address that keeps reconnecting."""
        now = self.clock()
        if self.last_log is None or now - self.last_log >= every:
            self.last_log = now
            return True
        self.unlogged += 1
        return False

    def penalize(self):
        for b in (self.bytes, self.messages, self.errors):
            b.penalize()

    def rested(self):
        return all(b.full() for b in (self.bytes, self.messages, self.errors))


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
