"""The page's HTTP server: static files of www/, package:// resources under /package/,
and /config.json (where the page finds rosbridge). Standard library only, no ROS."""
import json
import mimetypes
import os
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

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


def make_handler(www_root, find_package, config, log=None):
    """A request handler class bound to the page's root, a package lookup and the config."""
    config_body = json.dumps(config).encode()

    class Handler(BaseHTTPRequestHandler):
        server_version = 'course_web/0.1'

        def do_GET(self):
            self._answer(send_body=True)

        def do_HEAD(self):
            self._answer(send_body=False)

        def _answer(self, send_body):
            if self.path.split('?')[0] == '/config.json':
                return self._send(200, 'application/json', config_body, send_body)
            try:
                path = resolve(self.path, www_root, find_package)
                with open(path, 'rb') as f:
                    body = f.read()
            except ResolveError as e:
                return self._send(e.status, 'text/plain', (e.reason + '\n').encode(), send_body)
            except OSError as e:
                return self._send(404, 'text/plain', ('%s\n' % e.strerror).encode(), send_body)
            self._send(200, content_type(path), body, send_body)

        def _send(self, status, ctype, body, send_body):
            self.send_response(status)
            self.send_header('Content-Type', ctype)
            self.send_header('Content-Length', str(len(body)))
            self.send_header('Cache-Control', 'no-cache')
            self.send_header('Access-Control-Allow-Origin', '*')
            self.end_headers()
            if send_body:
                self.wfile.write(body)

        def log_message(self, fmt, *args):  # per-request lines go to DEBUG, not stderr
            if log:
                log(fmt % args)

    return Handler


def start_server(address, port, www_root, find_package, config, log=None):
    """Starts serving in a daemon thread; returns the server (call .shutdown() to stop)."""
    if not os.path.isfile(os.path.join(www_root, 'index.html')):
        raise ServerError('no index.html in %s' % www_root)
    try:
        httpd = ThreadingHTTPServer((address, port), make_handler(www_root, find_package, config, log))
    except OSError as e:
        raise ServerError('cannot listen on %s:%d: %s (choose another port: roslaunch course_web '
                          'web.launch port:=NNNN)' % (address or '0.0.0.0', port, e.strerror))
    httpd.daemon_threads = True
    threading.Thread(target=httpd.serve_forever, name='course_web_http', daemon=True).start()
    return httpd
