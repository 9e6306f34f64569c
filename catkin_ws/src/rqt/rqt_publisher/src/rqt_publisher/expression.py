"""Message Publisher maths (no Qt, no ROS): evaluating field expressions and filling messages.

Expressions are Python evaluated with the public names of `math`, `random` and `time`, `genpy`
(when importable) and `i`, the message counter (1 for the first message).
"""
import math
import random
import re
import time

INT_TYPES = {'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32', 'int64', 'uint64', 'byte', 'char'}
FLOAT_TYPES = {'float32', 'float64'}
_ARRAY = re.compile(r'^(.*)\[(\d*)\]$')


class ExpressionError(Exception):
    """The text to show in the expression cell (the original's `<expr> # error ...`)."""


def _base_locals():
    names = {}
    for module in (math, random, time):
        names.update({k: getattr(module, k) for k in dir(module) if not k.startswith('_')})
    try:
        import genpy
        names['genpy'] = genpy
    except ImportError:
        pass
    return names


_LOCALS = _base_locals()


def split_array(slot_type):
    """('float64', None) for a scalar; ('float64', n or -1) for an array (-1: variable)."""
    m = _ARRAY.match(slot_type)
    if not m:
        return slot_type, None
    return m.group(1), int(m.group(2)) if m.group(2) else -1


def python_types(slot_type, message_class_fn=None):
    """The accepted Python types of a field of ROS type `slot_type`."""
    base, array = split_array(slot_type)
    if array is not None:
        if base in ('uint8', 'char'):
            return (bytes, list, tuple)
        return (list, tuple)
    if base in INT_TYPES:
        return (int,)
    if base in FLOAT_TYPES:
        return (float,)
    if base == 'string':
        return (str,)
    if base == 'bool':
        return (bool,)
    if base in ('time', 'duration'):
        import genpy
        return (genpy.Time,) if base == 'time' else (genpy.Duration,)
    if message_class_fn is not None:
        cls = message_class_fn(base)
        if cls is not None:
            return (cls,)
    return (object,)


def evaluate(expression, slot_type, counter, message_class_fn=None):
    """The value of `expression` for a field of type `slot_type`, converted as the original does
    (int<->float, list<->tuple); raises ExpressionError with the cell text on failure."""
    types = python_types(slot_type, message_class_fn)
    names = dict(_LOCALS)
    names['i'] = counter
    base, array = split_array(slot_type)
    try:
        value = eval(expression, {}, names)
    except Exception:
        if str in types:
            return expression
        raise ExpressionError('%s # error evaluating as "%s"' % (expression, slot_type))
    ok = isinstance(value, types)
    if ok and isinstance(value, bool) and bool not in types:
        ok = False                       # True for an int field: converted below
    if ok:
        return value
    if int in types and isinstance(value, bool):
        return int(value)
    if float in types and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if int in types and isinstance(value, float) and value.is_integer():
        return int(value)
    if tuple in types and isinstance(value, list):
        return tuple(value)
    if list in types and isinstance(value, tuple):
        return list(value)
    if bool in types and isinstance(value, int):
        return bool(value)
    raise ExpressionError('%s # error evaluating as "%s"' % (expression, slot_type))


def field_paths(msg_class, prefix='', get_class=None):
    """[(path, slot type)] of every field of a message class, depth first ('' = the message)."""
    out = []
    for name, slot_type in zip(msg_class.__slots__, msg_class._slot_types):
        path = '%s/%s' % (prefix, name)
        out.append((path, slot_type))
        base, array = split_array(slot_type)
        if array is None and get_class is not None:
            sub = get_class(base)
            if sub is not None and hasattr(sub, '__slots__'):
                out.extend(field_paths(sub, path, get_class))
    return out


def slot_type_of(msg_class, path, get_class):
    """The ROS type of field `path` ('/linear/x', '/data[2]') of a message class."""
    cls = msg_class
    slot_type = None
    for part in [p for p in path.split('/') if p]:
        m = re.match(r'^(\w+)(?:\[(\d+)\])?$', part)
        if not m or cls is None or m.group(1) not in getattr(cls, '__slots__', []):
            raise ExpressionError('no field "%s" in %s' % (path, getattr(cls, '_type', '?')))
        slot_type = cls._slot_types[cls.__slots__.index(m.group(1))]
        if m.group(2) is not None:
            slot_type = split_array(slot_type)[0]
        cls = get_class(split_array(slot_type)[0])
    return slot_type


def set_field(msg, path, value):
    parts = [p for p in path.split('/') if p]
    obj = msg
    for part in parts[:-1]:
        obj = _get(obj, part)
    last = parts[-1]
    m = re.match(r'^(\w+)\[(\d+)\]$', last)
    if m:
        seq = getattr(obj, m.group(1))
        idx = int(m.group(2))
        if isinstance(seq, tuple):
            seq = list(seq)
        while len(seq) <= idx:
            seq.append(type(value)() if not hasattr(value, '__slots__') else type(value)())
        seq[idx] = value
        setattr(obj, m.group(1), seq)
    else:
        setattr(obj, last, value)


def _get(obj, part):
    m = re.match(r'^(\w+)(?:\[(\d+)\])?$', part)
    value = getattr(obj, m.group(1))
    if m.group(2) is not None:
        value = value[int(m.group(2))]
    return value


def fill_message(msg_class, expressions, counter, get_class):
    """A message with every expression {field path: text} evaluated; (msg, {path: error text})."""
    msg = msg_class()
    errors = {}
    # shorter paths first: a whole sub-message expression is applied before its fields
    for path in sorted(expressions, key=lambda p: (p.count('/'), p)):
        text = expressions[path]
        if text is None or str(text).strip() == '':
            continue
        try:
            slot_type = slot_type_of(msg_class, path, get_class)
            value = evaluate(str(text), slot_type, counter, get_class)
            set_field(msg, path, value)
        except ExpressionError as e:
            errors[path] = str(e)
    return msg, errors


def format_rate(rate):
    return '%.2f' % float(rate)
