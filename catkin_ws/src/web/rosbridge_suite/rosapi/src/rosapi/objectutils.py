"""Type definitions as rosapi's TypeDef (type, fieldnames, fieldtypes, fieldarraylen,
examples, constnames, constvalues) for a message type and every type it contains, and the
full definition text ("gendeps --cat" format) of topics_and_raw_types. Works on the generated
message classes; needs no master."""
from rosbridge_library.internal import ros_loader
from rosbridge_library.internal.message_conversion import fields_of


def _constants(cls):
    """(names, values) of the constants in the type's own definition text."""
    names, values = [], []
    own = cls._full_text.split('\n' + '=' * 80 + '\n', 1)[0]
    for line in own.splitlines():
        line = line.strip()
        if not line.startswith('string '):
            line = line.split('#', 1)[0].strip()
        if not line or '=' not in line:
            continue
        left, value = line.split('=', 1)
        parts = left.split()
        if len(parts) == 2:
            names.append(parts[1])
            values.append(value.strip())
    return names, values


def typedef(cls):
    inst = cls()
    d = {'type': cls._type, 'fieldnames': [], 'fieldtypes': [], 'fieldarraylen': [],
         'examples': [], 'constnames': [], 'constvalues': []}
    for f in fields_of(cls):
        d['fieldnames'].append(f.name)
        base = 'std_msgs/Header' if f.is_header else f.base
        d['fieldtypes'].append(base)
        d['fieldarraylen'].append(-1 if not f.is_array else (f.length or 0))
        if f.is_array:
            d['examples'].append('[]')
        elif f.cls is not None or f.base in ('time', 'duration'):
            d['examples'].append('{}')
        else:
            d['examples'].append(str(getattr(inst, f.name)))
    d['constnames'], d['constvalues'] = _constants(cls)
    return d


def typedefs_of_class(cls):
    """TypeDefs of cls and every message type it contains, cls first."""
    out, seen, todo = [], set(), [cls]
    while todo:
        c = todo.pop(0)
        if c._type in seen:
            continue
        seen.add(c._type)
        out.append(typedef(c))
        todo.extend(f.cls for f in fields_of(c) if f.cls is not None)
    return out


def message_typedefs(msg_type):
    return typedefs_of_class(ros_loader.get_message_class(msg_type))


def service_request_typedefs(srv_type):
    return typedefs_of_class(ros_loader.get_service_class(srv_type)._request_class)


def service_response_typedefs(srv_type):
    return typedefs_of_class(ros_loader.get_service_class(srv_type)._response_class)


def full_text(msg_type):
    """The type's definition followed by those of its dependencies, as in a bag file."""
    return ros_loader.get_message_class(msg_type)._full_text
