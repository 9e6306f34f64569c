"""ROS side of rqt_plot, no Qt: command-line field specs, field paths checked against message
classes, value extraction, and ROSData (a subscriber filling lock-protected buffers).

A *spec* is what the user types: `/turtle1/pose/x`, `/imu/linear_acceleration/x`,
`/joint_states/velocity[0]`. It is the topic name followed by a field path; where the topic ends
is only known once the topic is published, so specs are matched against the master's topic list.
"""
import re
import threading

import genmsg.msgs

NUMERIC = {'bool', 'byte', 'char', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32',
           'int64', 'uint64', 'float32', 'float64'}
TIMES = {'time', 'duration'}
_COMPONENT = re.compile(r'^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$')


class PlotFieldError(Exception):
    """A spec or field that cannot be plotted; the message names it."""


def expand_specs(args):
    """Command-line arguments -> list of specs.

    `a,b` gives both a and b; `/topic/f1:f2:f3` is shorthand for /topic/f1 /topic/f2 /topic/f3.
    """
    specs = []
    for arg in args:
        for part in [p for p in arg.split(',') if p]:
            if ':' in part:
                first, *rest = part.split(':')
                if '/' not in first.strip('/'):
                    raise PlotFieldError('%s: the shorthand needs a topic and a field before ":" '
                                         '(e.g. /turtle1/pose/x:y)' % part)
                base = first.rstrip('/').rsplit('/', 1)[0]
                specs.append(first)
                specs.extend('%s/%s' % (base, f) for f in rest if f)
            else:
                specs.append(part)
    return specs


def parse_field_path(path):
    """'a/b[2]/c' -> [('a', None), ('b', 2), ('c', None)]; '' -> []."""
    out = []
    for comp in [c for c in path.split('/') if c]:
        m = _COMPONENT.match(comp)
        if not m:
            raise PlotFieldError("bad field name '%s' in '%s'" % (comp, path))
        out.append((m.group(1), None if m.group(2) is None else int(m.group(2))))
    return out


def format_path(path):
    return '/'.join(n if i is None else '%s[%d]' % (n, i) for n, i in path)


def match_topic(spec, topics):
    """The published topic that `spec` starts with: (topic, type, field path string) or None.

    topics: {topic name: type name}. The longest topic that equals the spec or is followed in
    it by '/' wins.
    """
    best = None
    for name in topics:
        stem = name.rstrip('/')
        if spec.rstrip('/') == stem or spec.startswith(stem + '/'):
            if best is None or len(stem) > len(best.rstrip('/')):
                best = name
    if best is None:
        return None
    return best, topics[best], spec[len(best.rstrip('/')):].strip('/')


def _message_class(type_name):
    import roslib.message
    cls = roslib.message.get_message_class(type_name)
    if cls is None:
        raise PlotFieldError('message type %s is not known here (is its package built and '
                             'sourced?)' % type_name)
    return cls


def _slot_type(cls, name):
    return cls._slot_types[cls.__slots__.index(name)]


def check_field(msg_class, path, spec='', get_class=_message_class):
    """Type name of the field at `path` (parsed) if it is plottable, else PlotFieldError.

    Plottable: numbers, bool, time/duration, and elements of arrays selected by [index].
    Returns the message class instead when `path` ends at a (sub)message.
    """
    cls, type_name = msg_class, msg_class._type
    for depth, (name, index) in enumerate(path):
        if cls is None:
            raise PlotFieldError("%s: '%s' is a %s and has no field '%s'"
                                 % (spec, format_path(path[:depth]), type_name, name))
        if name not in cls.__slots__:
            raise PlotFieldError("%s: %s has no field '%s' (its fields: %s)"
                                 % (spec, cls._type, name, ', '.join(cls.__slots__)))
        type_name = _slot_type(cls, name)
        base, is_array, size = genmsg.msgs.parse_type(type_name)
        if index is not None:
            if not is_array:
                raise PlotFieldError("%s: field '%s' is a %s, not an array" % (spec, name, type_name))
            if size is not None and index >= size:
                raise PlotFieldError('%s: index %d is out of range for %s' % (spec, index, type_name))
            type_name = base
        elif is_array:
            raise PlotFieldError("%s: field '%s' is an array (%s); plot one element, e.g. %s[0]"
                                 % (spec, name, type_name, spec.rstrip('/')))
        cls = None if base in NUMERIC or base in TIMES or base == 'string' else get_class(base)
    if cls is not None:
        return cls
    if type_name not in NUMERIC and type_name not in TIMES:
        raise PlotFieldError('%s: field is a %s, not a number' % (spec, type_name))
    return type_name


def plottable_children(cls, spec):
    """Specs of the scalar numeric fields directly inside message class `cls` (used when a spec
    names a message rather than a number, e.g. `/turtle1/pose`)."""
    out = []
    for name, type_name in zip(cls.__slots__, cls._slot_types):
        base, is_array, size = genmsg.msgs.parse_type(type_name)
        if (base in NUMERIC or base in TIMES) and not is_array:
            out.append('%s/%s' % (spec.rstrip('/'), name))
    return out


def resolve_spec(spec, topics, get_class=_message_class):
    """Match `spec` against the published `topics` ({name: type}).

    Returns None while its topic is not published, else a list of (spec, topic, msg_class, path)
    to plot: one entry, or one per numeric field when the spec names a message. Raises
    PlotFieldError naming the spec when it cannot be plotted.
    """
    found = match_topic(spec, topics)
    if found is None:
        return None
    topic, type_name, field = found
    msg_class = get_class(type_name)
    path = parse_field_path(field)
    result = check_field(msg_class, path, spec, get_class)
    if isinstance(result, str):
        return [(spec, topic, msg_class, path)]
    children = plottable_children(result, spec)
    if not children:
        raise PlotFieldError('%s: %s has no numeric fields of its own; name a field inside it '
                             '(its fields: %s)' % (spec, result._type, ', '.join(result.__slots__)))
    return [(c, topic, msg_class, parse_field_path(c[len(topic.rstrip('/')):])) for c in children]


def extract(msg, path):
    """The float value at `path` (parsed) in `msg`."""
    value = msg
    for name, index in path:
        value = getattr(value, name)
        if index is not None:
            if index >= len(value):
                raise PlotFieldError('index %d is out of range (the array has %d elements)'
                                     % (index, len(value)))
            value = value[index]
    if hasattr(value, 'to_sec'):
        return value.to_sec()
    if isinstance(value, bytes):      # a single char/byte given as bytes
        return float(value[0])
    return float(value)


class ROSData:
    """Subscribes to `topic` and buffers (time [s since start_time], value) of one field.

    The callback only fills buffers under a lock; an error raised while extracting is stored and
    re-raised from next() on the consumer (GUI) thread.
    """

    def __init__(self, spec, topic, msg_class, path, start_time, subscribe=True):
        self.spec = spec
        self.topic = topic
        self.path = path
        self.start_time = start_time
        self.lock = threading.Lock()
        self.buff_x = []
        self.buff_y = []
        self.error = None
        self.count = 0
        self.sub = None
        if subscribe:
            import rospy
            self.sub = rospy.Subscriber(topic, msg_class, self._callback, queue_size=100)

    def _now(self):
        import rospy
        return rospy.get_time()

    def _callback(self, msg):
        try:
            value = extract(msg, self.path)
            stamp = 0.0
            if msg.__slots__ and msg.__slots__[0] == 'header':
                stamp = msg.header.stamp.to_sec()
            t = (stamp if stamp > 0.0 else self._now()) - self.start_time
        except Exception as e:  # handed over to the GUI thread, never lost in the callback
            with self.lock:
                self.error = PlotFieldError('%s: %s' % (self.spec, e))
            return
        with self.lock:
            self.buff_x.append(t)
            self.buff_y.append(value)
            self.count += 1

    def next(self):
        """New (xs, ys) since the last call; raises the callback's error if there was one."""
        with self.lock:
            if self.error is not None:
                error, self.error = self.error, None
                raise error
            xs, ys = self.buff_x, self.buff_y
            self.buff_x, self.buff_y = [], []
        return xs, ys

    def close(self):
        if self.sub is not None:
            self.sub.unregister()
            self.sub = None
