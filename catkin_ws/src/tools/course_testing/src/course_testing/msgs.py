"""The generated Python classes of a message package, for the md5 tests of our re-implemented
message packages (gazebo_msgs, control_msgs, controller_manager_msgs, ...)."""
import importlib


def md5_of(pkg, kind, name):
    """The md5 sum of pkg's generated class `name` (kind 'msg' or 'srv')."""
    return getattr(importlib.import_module('%s.%s' % (pkg, kind)), name)._md5sum


def generated_types(pkg):
    """{(kind, name)} of every message and service pkg generates (a service module also holds
    each service's FooRequest/FooResponse classes: only the service itself counts)."""
    names = set()
    for kind in ('msg', 'srv'):
        try:
            module = importlib.import_module('%s.%s' % (pkg, kind))
        except ImportError:
            continue
        for attr in dir(module):
            cls = getattr(module, attr)
            if not (isinstance(cls, type) and hasattr(cls, '_md5sum')):
                continue
            if kind == 'msg' or hasattr(cls, '_request_class'):
                names.add((kind, attr))
    return names
