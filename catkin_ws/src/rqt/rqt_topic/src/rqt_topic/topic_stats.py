"""Topic Monitor statistics (no Qt, no ROS): rate (Hz) and bandwidth of one topic, value rows."""
import collections

HZ_WINDOW = 100
BW_WINDOW = 99


class TopicStats(object):
    """Arrival times and serialized sizes of the latest messages of one topic."""

    def __init__(self, hz_window=HZ_WINDOW, bw_window=BW_WINDOW):
        self.times = collections.deque(maxlen=hz_window + 1)
        self.bw = collections.deque(maxlen=bw_window)    # (time, size)
        self.last_message = None

    def add(self, t, size, message=None):
        self.times.append(t)
        self.bw.append((t, size))
        self.last_message = message

    def hz(self):
        """Mean rate over the window (1 / mean inter-arrival time), or None."""
        if len(self.times) < 2:
            return None
        span = self.times[-1] - self.times[0]
        if span <= 0:
            return None
        return (len(self.times) - 1) / span

    def bandwidth(self, now):
        """Bytes per second: sizes of the last messages over (now - oldest stamp), or None."""
        if len(self.bw) < 2:
            return None
        oldest = self.bw[0][0]
        if now <= oldest:
            return None
        return sum(s for _, s in self.bw) / (now - oldest)


def format_hz(hz):
    return 'unknown' if hz is None else '%1.2f' % hz


def format_bandwidth(bw):
    if bw is None:
        return 'unknown'
    if bw < 1000:
        return '%.2fB/s' % bw
    if bw < 1000000:
        return '%.2fKB/s' % (bw / 1000.)
    return '%.2fMB/s' % (bw / 1000000.)


def value_rows(message, prefix=''):
    """[(path, repr text)] of every leaf field of a message (arrays of messages by index)."""
    rows = []
    slots = getattr(message, '__slots__', None)
    if slots is None:
        return [(prefix, repr(message))]
    for name in slots:
        value = getattr(message, name)
        path = '%s/%s' % (prefix, name)
        if hasattr(value, '__slots__'):
            rows.extend(value_rows(value, path))
        elif isinstance(value, (list, tuple)) and value and hasattr(value[0], '__slots__'):
            for i, v in enumerate(value):
                rows.extend(value_rows(v, '%s[%d]' % (path, i)))
        else:
            rows.append((path, repr(value)))
    return rows
