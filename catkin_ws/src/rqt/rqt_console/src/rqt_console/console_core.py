"""Console model (no Qt, no ROS): the message buffer, exclude/highlight filters, CSV files."""
import csv
import io
import re
import time

DEBUG, INFO, WARN, ERROR, FATAL = 1, 2, 4, 8, 16
SEVERITY_LABELS = {DEBUG: 'Debug', INFO: 'Info', WARN: 'Warn', ERROR: 'Error', FATAL: 'Fatal'}
SEVERITY_COLORS = {DEBUG: 'darkCyan', INFO: 'darkBlue', WARN: 'darkYellow', ERROR: 'darkRed', FATAL: 'red'}
COLUMNS = ['#', 'Message', 'Severity', 'Node', 'Stamp', 'Topics', 'Location']
CSV_HEADER = ['message', 'severity', 'node', 'stamp', 'topics', 'location']
DEFAULT_LIMIT = 20000


class Message(object):
    __slots__ = ('id', 'message', 'severity', 'node', 'stamp', 'topics', 'location')

    def __init__(self, message='', severity=INFO, node='', stamp=(0, 0), topics=(), location='', id=0):
        self.id = id
        self.message = message
        self.severity = severity
        self.node = node
        self.stamp = stamp               # (secs, nsecs)
        self.topics = list(topics)
        self.location = location

    def stamp_text(self):
        secs, nsecs = self.stamp
        t = time.localtime(secs)
        return '%s.%09d (%s)' % (time.strftime('%H:%M:%S', t), nsecs, time.strftime('%Y-%m-%d', t))

    def columns(self):
        return [str(self.id), self.message, SEVERITY_LABELS.get(self.severity, str(self.severity)),
                self.node, self.stamp_text(), ', '.join(self.topics), self.location]


class Filter(object):
    """One filter rule; `kind` is message, severity, node, topic, location, time or custom."""

    def __init__(self, kind, text='', regex=False, severities=(), nodes=(), topics=(),
                 start=None, end=None, enabled=True):
        self.kind = kind
        self.text = text
        self.regex = regex
        self.severities = set(severities)
        self.nodes = set(nodes)
        self.topics = set(topics)
        self.start, self.end = start, end
        self.enabled = enabled

    def _text_match(self, value):
        if not self.text:
            return False
        if self.regex:
            try:
                return re.search(self.text, value) is not None
            except re.error:
                return False
        return self.text in value

    def is_active(self):
        if not self.enabled:
            return False
        if self.kind in ('message', 'location'):
            return bool(self.text)
        if self.kind == 'severity':
            return bool(self.severities)
        if self.kind == 'node':
            return bool(self.nodes)
        if self.kind == 'topic':
            return bool(self.topics)
        if self.kind == 'time':
            return self.start is not None
        if self.kind == 'custom':
            return bool(self.severities or self.nodes or self.topics or self.text)
        return False

    def matches(self, m):
        if not self.is_active():
            return False
        if self.kind == 'message':
            return self._text_match(m.message)
        if self.kind == 'location':
            return self._text_match(m.location)
        if self.kind == 'severity':
            return m.severity in self.severities
        if self.kind == 'node':
            return m.node in self.nodes
        if self.kind == 'topic':
            return bool(self.topics & set(m.topics))
        if self.kind == 'time':
            t = m.stamp[0] + m.stamp[1] * 1e-9
            return t >= self.start and (self.end is None or t <= self.end)
        if self.kind == 'custom':
            ok = True
            if self.severities:
                ok = ok and m.severity in self.severities
            if self.nodes:
                ok = ok and m.node in self.nodes
            if self.topics:
                ok = ok and bool(self.topics & set(m.topics))
            if self.text:
                ok = ok and self._text_match(m.message)
            return ok
        return False


class ConsoleModel(object):
    """Messages newest first, limited to `limit`; the visible subset after filtering."""

    def __init__(self, limit=DEFAULT_LIMIT):
        self.limit = limit
        self.messages = []               # newest first
        self.exclude = []
        self.highlight = []
        self.show_highlighted_only = False
        self._next_id = 1

    def add(self, messages):
        for m in messages:
            m.id = self._next_id
            self._next_id += 1
        self.messages[0:0] = list(reversed(messages))
        del self.messages[self.limit:]

    def set_limit(self, limit):
        self.limit = int(limit)
        del self.messages[self.limit:]

    def is_highlighted(self, m):
        active = [f for f in self.highlight if f.is_active()]
        return not active or any(f.matches(m) for f in active)

    def visible(self):
        out = []
        for m in self.messages:
            if any(f.matches(m) for f in self.exclude):
                continue
            if self.show_highlighted_only and not self.is_highlighted(m):
                continue
            out.append(m)
        return out

    def status_text(self, shown):
        if shown == len(self.messages):
            return 'Displaying %d messages' % shown
        return 'Displaying %d of %d messages' % (shown, len(self.messages))

    def clear(self):
        self.messages = []


def to_csv(messages):
    buf = io.StringIO()
    w = csv.writer(buf, delimiter=';', quoting=csv.QUOTE_ALL, lineterminator='\n')
    w.writerow(CSV_HEADER)
    for m in messages:
        w.writerow([m.message, str(m.severity), m.node, '%d.%09d' % m.stamp, ','.join(m.topics), m.location])
    return buf.getvalue()


def from_csv(text):
    """Messages of a saved file; raises ValueError naming what is wrong."""
    rows = list(csv.reader(io.StringIO(text), delimiter=';'))
    if not rows or [r.lower() for r in rows[0]] != CSV_HEADER:
        raise ValueError('not an rqt_console file: the header must be %s' % ';'.join(CSV_HEADER))
    out = []
    for n, r in enumerate(rows[1:], 2):
        if not r:
            continue
        if len(r) != len(CSV_HEADER):
            raise ValueError('line %d has %d fields, expected %d' % (n, len(r), len(CSV_HEADER)))
        try:
            secs, _, nsecs = r[3].partition('.')
            out.append(Message(r[0], int(r[1]), r[2], (int(secs), int(nsecs or 0)),
                               [t for t in r[4].split(',') if t], r[5]))
        except ValueError as e:
            raise ValueError('line %d: %s' % (n, e))
    return out
