"""The page's HTTP server: static files of www/, package:// resources under /package/,
/config.json (where the page finds rosbridge) and /rosauth (a fresh rosauth `auth` message for
the page's rosbridge connection). Standard library only, no ROS.

With a token (as Jupyter's) every answer needs it: `?token=...` once (the answer sets a
cookie and redirects to the same URL without it), then the cookie, or an
`Authorization: token ...` header; anything else is 403."""
import hmac
import json
import mimetypes
import os
import secrets
import threading
from http.cookies import CookieError, SimpleCookie
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qsl, urlencode, urlsplit, urlunsplit

from .resolver import ResolveError, resolve

_TYPES = {
    '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json',
    '.html': 'text/html; charset=utf-8', '.css': 'text/css', '.stl': 'model/stl',
    '.dae': 'model/vnd.collada+xml', '.urdf': 'application/xml', '.xacro': 'application/xml',
    '.png': 'image/png', '.jpg': 'image/jpeg', '.svg': 'image/svg+xml',
}


def content_type(path):
    ext = os.path.splitext(path)[1].lower()
    return _TYPES.get(ext) or mimetypes.guess_type(path)[0] or 'application/octet-stream'


class ServerError(Exception):
    """The server cannot start (the message says why and what to change)."""


def new_token():
    return secrets.token_hex(24)


def cookie_name(port):
    """Cookies are shared by every port of a host: one name per port."""
    return 'course_web_token_%d' % port


def token_matches(given, token):
    """Constant-time comparison (a wrong guess takes as long whatever its prefix)."""
    if not isinstance(given, str):
        return False
    return hmac.compare_digest(given.encode('utf-8', 'replace'), token.encode('utf-8'))


def without_token(path):
    """The request path with the token query parameter removed."""
    parts = urlsplit(path)
    query = [(k, v) for k, v in parse_qsl(parts.query, keep_blank_values=True) if k != 'token']
    return urlunsplit(('', '', parts.path or '/', urlencode(query), ''))


class Handler(BaseHTTPRequestHandler):
    """course_web's requests; make_handler binds the class attributes below."""
    www_root = find_package = config_body = log = token = auth_issuer = None
    routes = {}
    server_version = 'course_web/0.1'

    def do_GET(self):
        self._answer(send_body=True)

    def do_HEAD(self):
        self._answer(send_body=False)

    def _token_state(self):
        """'ok', 'query' (right token in the URL: set the cookie) or None."""
        if self.token is None:
            return 'ok'
        query = dict(parse_qsl(urlsplit(self.path).query, keep_blank_values=True))
        if 'token' in query:
            return 'query' if token_matches(query['token'], self.token) else None
        header = self.headers.get('Authorization') or ''
        if header.lower().startswith('token '):
            return 'ok' if token_matches(header[6:].strip(), self.token) else None
        try:
            jar = SimpleCookie(self.headers.get('Cookie') or '')
        except CookieError:
            return None
        cookie = cookie_name(self.server.server_address[1])
        return 'ok' if cookie in jar and token_matches(jar[cookie].value, self.token) else None

    def _answer(self, send_body):
        state = self._token_state()
        if state is None:
            return self._send(403, 'text/plain', (
                '403 Forbidden: this page needs its token. Open the URL that '
                'course_web_server printed when it started (http://localhost:%d/?token=...)'
                '\n' % self.server.server_address[1]).encode(), send_body)
        if state == 'query':
            return self._redirect_with_cookie()
        path_only = self.path.split('?')[0]
        if path_only == '/config.json':
            return self._send(200, 'application/json', self.config_body, send_body)
        if path_only == '/rosauth':
            return self._rosauth(send_body)
        if path_only in self.routes:
            status, ctype, body = self.routes[path_only](urlsplit(self.path).query)
            return self._send(status, ctype, body, send_body)
        try:
            path = resolve(self.path, self.www_root, self.find_package)
            with open(path, 'rb') as f:
                body = f.read()
        except ResolveError as e:
            return self._send(e.status, 'text/plain', (e.reason + '\n').encode(), send_body)
        except OSError as e:
            return self._send(404, 'text/plain', ('%s\n' % e.strerror).encode(), send_body)
        self._send(200, content_type(path), body, send_body)

    def _redirect_with_cookie(self):
        """The right token in the URL: set it as the cookie and redirect to the URL without it."""
        self.send_response(302)
        self.send_header('Set-Cookie', '%s=%s; Path=/; HttpOnly; SameSite=Lax'
                         % (cookie_name(self.server.server_address[1]), self.token))
        self.send_header('Location', without_token(self.path))
        self.send_header('Content-Length', '0')
        self.send_header('Cache-Control', 'no-store')
        self.end_headers()

    def _rosauth(self, send_body):
        if self.auth_issuer is None:
            return self._send(404, 'text/plain', b'no rosauth secret here\n', send_body)
        host = (self.headers.get('Host') or '').rsplit(':', 1)[0].strip('[]')
        body = json.dumps(self.auth_issuer(self.client_address[0], host)).encode()
        return self._send(200, 'application/json', body, send_body, cache='no-store')

    def _send(self, status, ctype, body, send_body, cache='no-cache'):
        self.send_response(status)
        self.send_header('Content-Type', ctype)
        self.send_header('Content-Length', str(len(body)))
        self.send_header('Cache-Control', cache)
        if self.token is None:       # with a token, no other site's script may read answers
            self.send_header('Access-Control-Allow-Origin', '*')
        self.end_headers()
        if send_body:
            self.wfile.write(body)

    def log_message(self, fmt, *args):  # per-request lines go to DEBUG, not stderr
        if self.log:                    # (never the token: it is cut out of the line)
            text = fmt % args
            self.log(text.replace(self.token, '<token>') if self.token else text)


def make_handler(www_root, find_package, config, log=None, token=None, auth_issuer=None,
                 routes=None):
    """A request handler class bound to the page's root, a package lookup and the config.
    token: None = no token needed. auth_issuer(client ip, server host) -> the rosauth `auth`
    message for /rosauth (None: /rosauth is 404). routes: {path: handler(query string) ->
    (status, content type, body)} answered behind the same token (sim_library's Insert list)."""
    return type('Handler', (Handler,), {
        'www_root': www_root, 'find_package': staticmethod(find_package),
        'config_body': json.dumps(config).encode(), 'log': staticmethod(log) if log else None,
        'token': token, 'auth_issuer': staticmethod(auth_issuer) if auth_issuer else None,
        'routes': dict(routes or {})})


def start_server(address, port, www_root, find_package, config, log=None, token=None,
                 auth_issuer=None, routes=None):
    """Starts serving in a daemon thread; returns the server (call .shutdown() to stop)."""
    if not os.path.isfile(os.path.join(www_root, 'index.html')):
        raise ServerError('no index.html in %s' % www_root)
    try:
        httpd = ThreadingHTTPServer((address, port), make_handler(
            www_root, find_package, config, log, token, auth_issuer, routes))
    except OSError as e:
        raise ServerError('cannot listen on %s:%d: %s (choose another port: roslaunch course_web '
                          'web.launch port:=NNNN)' % (address or '0.0.0.0', port, e.strerror))
    httpd.daemon_threads = True
    threading.Thread(target=httpd.serve_forever, name='course_web_http', daemon=True).start()
    return httpd
