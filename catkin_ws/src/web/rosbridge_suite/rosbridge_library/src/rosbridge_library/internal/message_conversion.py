"""The one conversion module between ROS message objects (genpy classes) and JSON values.

As rosbridge_library's message_conversion: time and duration are ``{"secs", "nsecs"}``,
``uint8[]`` / ``char[]`` are base64 strings (raw bytes in CBOR), float NaN / ±inf become
``None`` (JSON null; a null sent for a float field reads back as NaN), a field the type lacks
is an error, a missing field keeps its default, and a ``std_msgs/Header`` whose stamp the
client did not set gets the current time.

Per-class field tables are compiled once and cached, so converting a message is one pass
over its slots.
"""
import base64
import math
import struct

from rosbridge_library.internal import ros_loader

INT_TYPES = {'int8': (-2 ** 7, 2 ** 7 - 1), 'uint8': (0, 2 ** 8 - 1),
             'int16': (-2 ** 15, 2 ** 15 - 1), 'uint16': (0, 2 ** 16 - 1),
             'int32': (-2 ** 31, 2 ** 31 - 1), 'uint32': (0, 2 ** 32 - 1),
             'int64': (-2 ** 63, 2 ** 63 - 1), 'uint64': (0, 2 ** 64 - 1),
             'byte': (-2 ** 7, 2 ** 7 - 1), 'char': (0, 2 ** 8 - 1)}
FLOAT_TYPES = {'float32', 'float64'}
TIME_TYPES = {'time', 'duration'}
BYTE_ARRAY_BASES = {'uint8', 'char'}
HEADER_TYPES = {'std_msgs/Header', 'Header', 'roslib/Header'}
# CBOR typed-array tags (draft-ietf-cbor-array-tags, little endian) for numeric arrays
CBOR_TAGS = {'uint8': (64, 'B'), 'uint16': (69, 'H'), 'uint32': (70, 'I'), 'uint64': (71, 'Q'),
             'int8': (72, 'b'), 'byte': (72, 'b'), 'int16': (77, 'h'), 'int32': (78, 'i'),
             'int64': (79, 'q'), 'float32': (85, 'f'), 'float64': (86, 'd')}

# field kinds
_PRIM, _FLOAT, _STR, _BOOL, _TIME, _MSG = range(6)


class ConversionError(Exception):
    """Base of the conversion errors; the text is what the client is told."""


class NonexistentFieldException(ConversionError):
    def __init__(self, basetype, fields):
        ConversionError.__init__(self, 'Message type %s does not have a field %s'
                                 % (basetype, '.'.join(fields)))


class FieldTypeMismatchException(ConversionError):
    def __init__(self, roottype, fields, expected_type, found_type):
        if fields:
            text = '%s message requires a %s for field %s, but got a %s' % (
                roottype, expected_type, '.'.join(fields), found_type)
        else:
            text = 'Expected a JSON object for type %s but received a %s' % (
                roottype, found_type)
        ConversionError.__init__(self, text)


def _type_name(value):
    return {dict: 'object', list: 'array', str: 'string', bool: 'bool', int: 'int',
            float: 'float', type(None): 'null'}.get(type(value), type(value).__name__)


class _Field(object):
    __slots__ = ('name', 'type', 'base', 'is_array', 'length', 'kind', 'cls', 'is_header')

    def __init__(self, name, slot_type):
        self.name = name
        self.type = slot_type
        base, self.is_array, self.length = parse_type(slot_type)
        self.base = base
        self.cls = None
        self.is_header = base in HEADER_TYPES
        if base in FLOAT_TYPES:
            self.kind = _FLOAT
        elif base in INT_TYPES:
            self.kind = _PRIM
        elif base == 'string':
            self.kind = _STR
        elif base == 'bool':
            self.kind = _BOOL
        elif base in TIME_TYPES:
            self.kind = _TIME
        else:
            self.kind = _MSG
            self.cls = ros_loader.get_message_class('std_msgs/Header' if self.is_header else base)


def parse_type(slot_type):
    """'float64[9]' -> ('float64', True, 9); 'uint8[]' -> ('uint8', True, None)."""
    if slot_type.endswith(']'):
        base, _, rest = slot_type.partition('[')
        n = rest[:-1]
        return base, True, int(n) if n else None
    return slot_type, False, None


_FIELD_CACHE = {}


def fields_of(cls):
    """The compiled field table of a genpy message class (cached)."""
    table = _FIELD_CACHE.get(cls)
    if table is None:
        table = [_Field(n, t) for n, t in zip(cls.__slots__, cls._slot_types)]
        _FIELD_CACHE[cls] = table
    return table


# ---------------------------------------------------------------------------- ROS -> JSON

def extract_values(inst, binary=False):
    """A dict of JSON values for a genpy message; `binary`: byte arrays stay bytes and numeric
    arrays become CBOR typed arrays (for the cbor compression)."""
    out = {}
    for f in fields_of(type(inst)):
        out[f.name] = _from_field(getattr(inst, f.name), f, binary)
    return out


def _from_field(value, f, binary):
    kind = f.kind
    if not f.is_array:
        if kind == _FLOAT:
            return value if math.isfinite(value) else None
        if kind == _MSG:
            return extract_values(value, binary)
        if kind == _TIME:
            return {'secs': value.secs, 'nsecs': value.nsecs}
        return value
    # arrays
    if f.base in BYTE_ARRAY_BASES:
        raw = value if isinstance(value, (bytes, bytearray)) else bytes(bytearray(value))
        return bytes(raw) if binary else base64.b64encode(raw).decode('ascii')
    if kind in (_FLOAT, _PRIM):
        if binary:
            return _cbor_typed_array(value, f.base)
        if kind == _FLOAT:
            return [x if math.isfinite(x) else None for x in value]
        return list(value)
    if kind == _MSG:
        return [extract_values(v, binary) for v in value]
    if kind == _TIME:
        return [{'secs': v.secs, 'nsecs': v.nsecs} for v in value]
    return list(value)


def _cbor_typed_array(values, base):
    import cbor2
    tag, code = CBOR_TAGS[base]
    return cbor2.CBORTag(tag, struct.pack('<%d%s' % (len(values), code), *values))


# ---------------------------------------------------------------------------- JSON -> ROS

def populate_instance(data, inst, now=None):
    """Fill the genpy message `inst` from the JSON dict `data`; returns inst.
    `now()` gives (secs, nsecs) for Header stamps the client left out (zero if None)."""
    roottype = inst._type
    _populate(data, inst, roottype, [], now)
    if now is not None:
        _stamp_missing_header(data, inst, now)
    return inst


def _populate(data, inst, roottype, path, now):
    if not isinstance(data, dict):
        raise FieldTypeMismatchException(roottype, path, inst._type, _type_name(data))
    table = fields_of(type(inst))
    names = {f.name for f in table}
    for key in data:
        if key not in names:
            raise NonexistentFieldException(inst._type, path + [key])
    for f in table:
        if f.name in data:
            setattr(inst, f.name, _to_field(data[f.name], f, roottype, path + [f.name], now))
    return inst


def _to_field(value, f, roottype, path, now):
    if not f.is_array:
        return _to_scalar(value, f, f.type, roottype, path, now)
    if f.base in BYTE_ARRAY_BASES:
        if isinstance(value, str):
            try:
                return base64.b64decode(value, validate=True)
            except (ValueError, TypeError):
                raise FieldTypeMismatchException(roottype, path, 'base64 string', 'string '
                                                 'that is not base64')
        if isinstance(value, (bytes, bytearray)):
            return bytes(value)
        if isinstance(value, list):
            lo, hi = INT_TYPES[f.base]
            for i, v in enumerate(value):
                if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
                    raise FieldTypeMismatchException(roottype, path + [str(i)], f.base,
                                                     _type_name(v))
            return bytes(value)
        raise FieldTypeMismatchException(roottype, path, f.type, _type_name(value))
    if not isinstance(value, list):
        raise FieldTypeMismatchException(roottype, path, f.type, _type_name(value))
    if f.length is not None and len(value) != f.length:
        raise FieldTypeMismatchException(roottype, path, f.type,
                                         'array of length %d' % len(value))
    return [_to_scalar(v, f, f.base, roottype, path + [str(i)], now)
            for i, v in enumerate(value)]


def _to_scalar(value, f, expected, roottype, path, now):
    kind = f.kind
    if kind == _FLOAT:
        if value is None:
            return float('nan')
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise FieldTypeMismatchException(roottype, path, f.base, _type_name(value))
        return float(value)
    if kind == _PRIM:
        if isinstance(value, bool) or not isinstance(value, int):
            raise FieldTypeMismatchException(roottype, path, f.base, _type_name(value))
        lo, hi = INT_TYPES[f.base]
        if not lo <= value <= hi:
            raise FieldTypeMismatchException(roottype, path, f.base,
                                             'value %d out of range' % value)
        return value
    if kind == _STR:
        if not isinstance(value, str):
            raise FieldTypeMismatchException(roottype, path, 'string', _type_name(value))
        return value
    if kind == _BOOL:
        if not isinstance(value, bool) and value not in (0, 1):
            raise FieldTypeMismatchException(roottype, path, 'bool', _type_name(value))
        return bool(value)
    if kind == _TIME:
        return _to_time(value, f.base, roottype, path, now)
    inst = f.cls()
    _populate(value, inst, roottype, path, now)
    if f.is_header and now is not None and isinstance(value, dict) and 'stamp' not in value:
        inst.stamp = _time_class('time')(*now())
    return inst


def _time_class(base):
    import genpy
    return genpy.Time if base == 'time' else genpy.Duration


def _to_time(value, base, roottype, path, now):
    cls = _time_class(base)
    if value == 'now' and base == 'time':
        return cls(*now()) if now is not None else cls()
    if isinstance(value, dict):
        unknown = set(value) - {'secs', 'nsecs', 'sec', 'nanosec'}
        if unknown:
            raise NonexistentFieldException(base, path + [sorted(unknown)[0]])
        secs = value.get('secs', value.get('sec', 0))
        nsecs = value.get('nsecs', value.get('nanosec', 0))
        if not all(isinstance(v, int) and not isinstance(v, bool) for v in (secs, nsecs)):
            raise FieldTypeMismatchException(roottype, path, base + ' {secs, nsecs} integers',
                                             'object')
        return cls(secs, nsecs)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return cls.from_sec(float(value))
    raise FieldTypeMismatchException(roottype, path, base, _type_name(value))


def _stamp_missing_header(data, inst, now):
    """A top-level Header the client omitted entirely gets the current time."""
    for f in fields_of(type(inst)):
        if f.is_header and not f.is_array and f.name not in data:
            getattr(inst, f.name).stamp = _time_class('time')(*now())
