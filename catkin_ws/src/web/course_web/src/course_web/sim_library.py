"""The 3D panel's Insert list: the simulator's model library as the desktop window shows it
(ode_sim.description.library, ROS-free), served by course_web_server as

  /sim/models.json                      [{name, title, uri, source, thumbnail}, ...]
  /sim/thumbnail?source=SOURCE&name=NAME   the model's thumbnail (PNG, rendered once, cached)

Every answer is (status, content type, body); a bad request is one line naming what is
wrong. No ROS imports (ode_sim's description package is plain Python)."""
import json
from urllib.parse import parse_qsl, urlencode


class LibraryError(Exception):
    def __init__(self, status, reason):
        super().__init__(reason)
        self.status, self.reason = status, reason


def _default_library():
    try:
        from ode_sim.description import library
    except ImportError as e:
        raise LibraryError(503, 'the model library (ode_sim.description.library) cannot be '
                                'loaded: %s' % e)
    return library


class SimLibrary(object):
    """lib: a module (or object) with list_models() and thumbnail(entry, size); default
    ode_sim.description.library, imported on first use."""

    def __init__(self, lib=None, size=128):
        self._lib = lib
        self.size = size

    @property
    def lib(self):
        if self._lib is None:
            self._lib = _default_library()
        return self._lib

    def entries(self):
        try:
            return list(self.lib.list_models())
        except LibraryError:
            raise
        except Exception as e:      # an unreadable model folder must not kill the page
            raise LibraryError(500, 'listing the model library failed: %s: %s'
                               % (type(e).__name__, e))

    def models(self):
        """The Insert list, in list_models()'s order (source, then name)."""
        return [{'name': e.name, 'title': getattr(e, 'title', '') or e.name, 'uri': e.uri,
                 'source': e.source,
                 'thumbnail': 'sim/thumbnail?' + urlencode({'source': e.source, 'name': e.name})}
                for e in self.entries()]

    def find(self, source, name):
        if not name:
            raise LibraryError(400, 'sim/thumbnail needs ?source=SOURCE&name=NAME')
        for e in self.entries():
            if e.name == name and (not source or e.source == source):
                return e
        raise LibraryError(404, 'no model "%s"%s in the model library' % (
            name, ' (source %s)' % source if source else ''))

    def thumbnail(self, source, name):
        entry = self.find(source, name)
        try:
            path = self.lib.thumbnail(entry, size=self.size)
            with open(path, 'rb') as f:
                return f.read()
        except Exception as e:
            raise LibraryError(500, 'no thumbnail of model "%s": %s: %s'
                               % (name, type(e).__name__, e))

    # ------------------------------------------------------------------ HTTP
    def routes(self):
        """{path: handler(query string) -> (status, content type, body bytes)} for
        server.make_handler's `routes`."""
        return {'/sim/models.json': self._models_route, '/sim/thumbnail': self._thumb_route}

    def _models_route(self, _query):
        try:
            return 200, 'application/json', json.dumps(self.models()).encode()
        except LibraryError as e:
            return e.status, 'text/plain', (e.reason + '\n').encode()

    def _thumb_route(self, query):
        q = dict(parse_qsl(query, keep_blank_values=True))
        try:
            return 200, 'image/png', self.thumbnail(q.get('source', ''), q.get('name', ''))
        except LibraryError as e:
            return e.status, 'text/plain', (e.reason + '\n').encode()
