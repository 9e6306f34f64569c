"""What every capability shares: argument checks with the original's messages, glob checks."""
import fnmatch


class MissingArgumentException(Exception):
    pass


class InvalidArgumentException(Exception):
    pass


class Capability(object):
    def __init__(self, protocol):
        self.protocol = protocol
        self.backend = protocol.backend

    @staticmethod
    def arg(msg, name, types, required=True, default=None):
        """msg[name] checked against `types` (a type or tuple of types)."""
        if name not in msg or msg[name] is None:
            if required:
                raise MissingArgumentException('Expected a %s field but none was found.' % name)
            return default
        value = msg[name]
        types = types if isinstance(types, tuple) else (types,)
        if isinstance(value, bool) and bool not in types:
            ok = False
        else:
            ok = isinstance(value, types)
        if not ok:
            raise InvalidArgumentException(
                'Expected field %s to be one of %s. Invalid value: %r'
                % (name, [t.__name__ for t in types], value))
        return value

    def allowed(self, name, glob_key):
        globs = self.protocol.settings.get(glob_key) or []
        return not globs or any(fnmatch.fnmatch(str(name), g) for g in globs)

    def finish(self):
        pass
