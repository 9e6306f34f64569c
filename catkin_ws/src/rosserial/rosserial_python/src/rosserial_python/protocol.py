"""The rosserial wire protocol, revision 1 (Hydro and later), with no ROS imports.

Frame: 0xFF, 0xFE, payload length (uint16 LE), length checksum, topic id (uint16 LE), payload,
data checksum. A checksum byte makes the sum of the bytes it covers ≡ 255 (mod 256).

Besides framing, this module reads and writes the few system messages the bridge handles
itself (TopicInfo, Log, RequestParam, std_msgs/Time) in the standard ROS 1 serialisation, so the
protocol core needs no generated message classes.
"""
import struct

SYNC_FLAG = 0xFF
PROTOCOL_VER1 = 0xFF   # rev 0 (rosserial 0.4, Groovy and earlier)
PROTOCOL_VER2 = 0xFE   # rev 1 (rosserial 0.5+, Hydro and later)
PROTOCOL_VER = PROTOCOL_VER2

# rosserial_msgs/TopicInfo constants
ID_PUBLISHER = 0
ID_SUBSCRIBER = 1
ID_SERVICE_SERVER = 2
ID_SERVICE_CLIENT = 4
ID_PARAMETER_REQUEST = 6
ID_LOG = 7
ID_TIME = 10
ID_TX_STOP = 11
FIRST_USER_ID = 100

MAX_PAYLOAD = 0x7FFF   # rosserial_python reads the length as a signed 16-bit value


def checksum(data):
    """The byte that makes sum(data) + byte ≡ 255 (mod 256)."""
    return 255 - (sum(data) % 256)


def encode_frame(topic_id, payload=b''):
    """One rev-1 frame carrying `payload` on `topic_id`."""
    payload = bytes(payload)
    if len(payload) > MAX_PAYLOAD:
        raise ValueError('rosserial payload of %d bytes exceeds %d' % (len(payload), MAX_PAYLOAD))
    length = struct.pack('<H', len(payload))
    topic = struct.pack('<H', topic_id)
    return (bytes([SYNC_FLAG, PROTOCOL_VER]) + length + bytes([checksum(length)]) + topic
            + payload + bytes([checksum(topic + payload)]))


REQUEST_TOPICS = encode_frame(ID_PUBLISHER)
TX_STOP = encode_frame(ID_TX_STOP)


class Frame(object):
    """A complete, checksum-valid frame."""
    kind = 'frame'

    def __init__(self, topic_id, payload):
        self.topic_id = topic_id
        self.payload = payload

    def __repr__(self):
        return 'Frame(%d, %r)' % (self.topic_id, self.payload)


class BadVersion(object):
    """A sync flag followed by something else than the rev-1 protocol byte."""
    kind = 'bad_version'

    def __init__(self, version):
        self.version = version

    def describe(self):
        if self.version == PROTOCOL_VER1:
            return 'Rev 0 (rosserial 0.4 and earlier)'
        if self.version == PROTOCOL_VER2:
            return 'Rev 1 (rosserial 0.5+)'
        return 'unrecognized (0x%02x)' % self.version


class BadLengthChecksum(object):
    kind = 'bad_length_checksum'

    def __init__(self, length):
        self.length = length


class BadDataChecksum(object):
    kind = 'bad_data_checksum'

    def __init__(self, topic_id, length):
        self.topic_id = topic_id
        self.length = length


class FrameParser(object):
    """Incremental frame parser: feed() any bytes, get the events they complete.

    Bytes before a sync flag are skipped (counted in `.garbage`). A frame with a bad checksum
    is reported and dropped, and parsing resumes right after its sync flag, so a frame hidden
    in garbage is still found and no later frame is lost. `.in_frame` tells whether a frame is
    partly received (the caller applies its read timeout to that)."""

    def __init__(self, max_payload=MAX_PAYLOAD):
        self.max_payload = max_payload
        self.buf = bytearray()
        self.garbage = 0

    @property
    def in_frame(self):
        return len(self.buf) > 0

    def reset(self):
        """Drop a partly received frame (after a read timeout)."""
        dropped = len(self.buf)
        del self.buf[:]
        return dropped

    def partial_step(self):
        """Which part of the frame a partial buffer is waiting for (for log messages)."""
        n = len(self.buf)
        if n < 2:
            return 'syncflag'
        if n < 5:
            return 'message length'
        if n < 7:
            return 'topic id'
        return 'data'

    def feed(self, data):
        self.buf.extend(data)
        events = []
        while True:
            ev = self._next()
            if ev is None:
                return events
            events.append(ev)

    def _resync(self, skip):
        """Drop `skip` bytes and everything up to the next sync flag."""
        del self.buf[:skip]
        i = self.buf.find(SYNC_FLAG)
        if i < 0:
            self.garbage += len(self.buf)
            del self.buf[:]
        else:
            self.garbage += i
            del self.buf[:i]

    def _next(self):
        buf = self.buf
        if not buf:
            return None
        if buf[0] != SYNC_FLAG:
            self._resync(0)
            if not self.buf:
                return None
        if len(buf) < 2:
            return None
        if buf[1] != PROTOCOL_VER:
            ev = BadVersion(buf[1])
            # a second 0xFF may itself start the next frame: keep it
            self._resync(1)
            return ev
        if len(buf) < 5:
            return None
        length = buf[2] | (buf[3] << 8)
        if (buf[2] + buf[3] + buf[4]) % 256 != 255 or length > self.max_payload:
            self._resync(1)
            return BadLengthChecksum(length)
        if len(buf) < 8 + length:
            return None
        topic_id = buf[5] | (buf[6] << 8)
        if sum(buf[5:8 + length]) % 256 != 255:
            self._resync(1)
            return BadDataChecksum(topic_id, length)
        payload = bytes(buf[7:7 + length])
        del buf[:8 + length]
        return Frame(topic_id, payload)


# -- system messages (standard ROS 1 serialisation) -------------------------------------------

class Reader(object):
    def __init__(self, data):
        self.data = bytes(data)
        self.pos = 0

    def take(self, fmt):
        size = struct.calcsize(fmt)
        if self.pos + size > len(self.data):
            raise ValueError('message truncated: %d bytes, needed %d more at offset %d'
                             % (len(self.data), size, self.pos))
        vals = struct.unpack_from(fmt, self.data, self.pos)
        self.pos += size
        return vals[0] if len(vals) == 1 else vals

    def string(self):
        n = self.take('<I')
        if self.pos + n > len(self.data):
            raise ValueError('string of %d bytes runs past the end of the message' % n)
        s = self.data[self.pos:self.pos + n]
        self.pos += n
        return s.decode('utf-8', 'replace')


def pack_string(s):
    b = s.encode('utf-8') if isinstance(s, str) else bytes(s)
    return struct.pack('<I', len(b)) + b


class TopicInfo(object):
    """rosserial_msgs/TopicInfo."""

    def __init__(self, topic_id=0, topic_name='', message_type='', md5sum='', buffer_size=0):
        self.topic_id = topic_id
        self.topic_name = topic_name
        self.message_type = message_type
        self.md5sum = md5sum
        self.buffer_size = buffer_size

    @classmethod
    def decode(cls, data):
        r = Reader(data)
        return cls(r.take('<H'), r.string(), r.string(), r.string(), r.take('<i'))

    def encode(self):
        return (struct.pack('<H', self.topic_id) + pack_string(self.topic_name)
                + pack_string(self.message_type) + pack_string(self.md5sum)
                + struct.pack('<i', self.buffer_size))


def decode_log(data):
    """rosserial_msgs/Log → (level, msg)."""
    r = Reader(data)
    return r.take('<B'), r.string()


def encode_log(level, msg):
    return struct.pack('<B', level) + pack_string(msg)


def decode_param_request(data):
    """rosserial_msgs/RequestParamRequest → name."""
    return Reader(data).string()


def encode_param_request(name):
    return pack_string(name)


def encode_param_response(ints=(), floats=(), strings=()):
    """rosserial_msgs/RequestParamResponse."""
    out = struct.pack('<I', len(ints)) + b''.join(struct.pack('<i', v) for v in ints)
    out += struct.pack('<I', len(floats)) + b''.join(struct.pack('<f', v) for v in floats)
    out += struct.pack('<I', len(strings)) + b''.join(pack_string(s) for s in strings)
    return out


def decode_param_response(data):
    r = Reader(data)
    ints = [r.take('<i') for _ in range(r.take('<I'))]
    floats = [r.take('<f') for _ in range(r.take('<I'))]
    strings = [r.string() for _ in range(r.take('<I'))]
    return ints, floats, strings


def encode_time(secs, nsecs):
    """std_msgs/Time."""
    return struct.pack('<II', secs, nsecs)


def decode_time(data):
    return Reader(data).take('<II')


class ParamError(ValueError):
    """A parameter value the protocol cannot carry."""


def param_to_response(name, value):
    """A parameter value → (ints, floats, strings) as RequestParamResponse carries it.
    bool/int → ints, float → floats, str → strings; a list must be homogeneous."""
    if isinstance(value, dict):
        raise ParamError('Cannot send param %s because it is a dictionary' % name)
    values = value if isinstance(value, (list, tuple)) else [value]
    if not values:
        return [], [], []
    kinds = set()
    for v in values:
        if isinstance(v, (bool, int)):
            kinds.add('int')
        elif isinstance(v, float):
            kinds.add('float')
        elif isinstance(v, str):
            kinds.add('str')
        else:
            raise ParamError('Cannot send param %s: values of type %s are not supported'
                             % (name, type(v).__name__))
    if len(kinds) != 1:
        raise ParamError('All Paramers in the list %s must be of the same type' % name)
    kind = kinds.pop()
    if kind == 'int':
        return [int(v) for v in values], [], []
    if kind == 'float':
        return [], [float(v) for v in values], []
    return [], [], list(values)
