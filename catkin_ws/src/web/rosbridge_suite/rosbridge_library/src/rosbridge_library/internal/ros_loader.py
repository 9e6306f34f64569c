"""Message and service classes by type string ('pkg/Type' or 'pkg/msg/Type'), cached.
Imports the generated Python modules directly; needs no master."""
import importlib
import threading

_lock = threading.Lock()
_cache = {}


class InvalidTypeStringException(Exception):
    def __init__(self, typestring):
        Exception.__init__(self, '%s is not a valid type string' % typestring)


class InvalidModuleException(Exception):
    def __init__(self, modname, subname, original):
        Exception.__init__(self, 'Unable to import %s.%s from package %s. Caused by: %s'
                           % (modname, subname, modname, original))


class InvalidClassException(Exception):
    def __init__(self, modname, subname, classname):
        Exception.__init__(self, 'Unable to import %s class %s from package %s. Caused by '
                           'module %s.%s has no class %s' % (subname, classname, modname,
                                                             modname, subname, classname))


def _split(typestring, kind):
    if not isinstance(typestring, str):
        raise InvalidTypeStringException(typestring)
    parts = typestring.strip('/').split('/')
    if len(parts) == 3 and parts[1] == kind:
        parts = [parts[0], parts[2]]
    if len(parts) != 2 or not all(parts):
        raise InvalidTypeStringException(typestring)
    return parts


def _load(typestring, kind):
    key = (typestring, kind)
    cls = _cache.get(key)
    if cls is not None:
        return cls
    pkg, name = _split(typestring, kind)
    with _lock:
        try:
            module = importlib.import_module('%s.%s' % (pkg, kind))
        except Exception as e:   # ImportError or a broken generated module
            raise InvalidModuleException(pkg, kind, e)
        cls = getattr(module, name, None)
        if cls is None or not hasattr(cls, '_type'):
            raise InvalidClassException(pkg, kind, name)
        _cache[key] = cls
    return cls


def get_message_class(typestring):
    return _load(typestring, 'msg')


def get_service_class(typestring):
    return _load(typestring, 'srv')


def get_message_instance(typestring):
    return get_message_class(typestring)()


def get_service_request_instance(typestring):
    return get_service_class(typestring)._request_class()


def get_service_response_instance(typestring):
    return get_service_class(typestring)._response_class()
