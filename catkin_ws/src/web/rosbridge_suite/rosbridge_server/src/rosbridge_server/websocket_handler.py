"""The WebSocket transport (tornado): one Protocol per connection, frames in on the IO loop,
frames out through the client's bounded queue and a writer that awaits each write.

No rospy here: the ROS side arrives as `Server.backend` and the `on_clients_changed` hook.
"""
import json
import logging
import threading
import time

from tornado import gen
from tornado.ioloop import IOLoop
from tornado.websocket import WebSocketClosedError, WebSocketHandler

from rosbridge_library.protocol import Protocol
from rosbridge_server.client_queue import ClientQueue
from rosbridge_server.limits import AddressBudgets, Counters

logger = logging.getLogger('rosout')


class Server(object):
    """State shared by the connections of one server."""

    def __init__(self, backend, settings, protocol_settings, on_clients_changed=None,
                 authenticator=None, counters=None):
        """authenticator(auth message dict) -> bool, blocking (called on a thread), or None:
        no authentication. counters: a limits.Counters."""
        self.backend = backend
        self.settings = settings
        self.counters = counters or Counters()
        self.protocol_settings = dict(protocol_settings, count=self.counters.add)
        self.authenticator = authenticator
        self.on_clients_changed = on_clients_changed or (lambda clients: None)
        self.lock = threading.Lock()
        self.next_id = 0
        self.clients = {}          # client id -> RosbridgeWebSocket
        self.budgets = {}          # client address -> AddressBudgets
        self.loop = None

    def add(self, handler):
        with self.lock:
            self.next_id += 1
            self.clients[self.next_id] = handler
            n = len(self.clients)
            cid = self.next_id
        self.on_clients_changed(self.snapshot())
        return cid, n

    def remove(self, cid):
        with self.lock:
            self.clients.pop(cid, None)
            n = len(self.clients)
        self.on_clients_changed(self.snapshot())
        return n

    def budgets_of(self, ip):
        """The shared incoming budgets of an address (kept while it is connected or has not
        rested since it was cut off)."""
        s = self.settings
        with self.lock:
            connected = {h.remote_ip for h in self.clients.values()}
            for old in [a for a, b in self.budgets.items()
                        if a not in connected and a != ip and b.rested()]:
                del self.budgets[old]
            b = self.budgets.get(ip)
            if b is None:
                b = self.budgets[ip] = AddressBudgets(s['max_client_bytes_per_second'],
                                                      s['max_client_messages_per_second'],
                                                      s['max_client_errors_per_second'])
            return b

    def connections_from(self, ip):
        with self.lock:
            return sum(1 for h in self.clients.values() if h.remote_ip == ip)

    def snapshot(self):
        """[(ip address, connection time)] of the connected clients."""
        with self.lock:
            return [(h.remote_ip, h.connected_at) for h in self.clients.values()]


class RosbridgeWebSocket(WebSocketHandler):
    def initialize(self, server):
        self.server = server
        self.protocol = None
        self.queue = None
        self.client_id = None
        self.remote_ip = ''
        self.connected_at = 0.0
        self.last_drop_log = 0.0
        self.authenticated = False
        self.auth_pending = False
        self.pending = []          # frames that came while the auth request was checked
        self.cut = False           # cut off: further frames are ignored

    def check_origin(self, origin):
        return True      # the course page is served from another port

    def get_compression_options(self):
        return {} if self.server.settings.get('use_compression') else None

    def open(self):
        s = self.server.settings
        self.loop = IOLoop.current()
        self.remote_ip = self.request.remote_ip or ''
        self.connected_at = time.time()
        limit = s['max_connections_per_address']
        if self.server.connections_from(self.remote_ip) >= limit:
            self.server.counters.add('connections_refused')
            reason = ('%d connections from %s already, the most max_connections_per_address '
                      'allows' % (limit, self.remote_ip))
            logger.warning('Refused a connection: %s' % reason)
            self._close_with_status(reason)
            return
        self.budgets = self.server.budgets_of(self.remote_ip)
        self.authenticated = self.server.authenticator is None
        self.queue = ClientQueue(s['max_client_queue_messages'], s['max_client_queue_bytes'])
        self.client_id, n = self.server.add(self)
        self.protocol = Protocol(self.client_id, self.server.backend, self._send_frame,
                                 self.server.protocol_settings)
        self.set_nodelay(True)
        logger.info('Client connected.  %d clients total.' % n)
        if not self.authenticated:
            self.loop.call_later(s['auth_timeout'], self._auth_timeout)

    def on_message(self, message):
        if self.cut or self.protocol is None:
            return
        s = self.server.settings
        if not self.budgets.bytes.take(len(message)):
            return self._cut_off('sent more than %d bytes a second'
                                 % s['max_client_bytes_per_second'])
        if not self.budgets.messages.take(1):
            return self._cut_off('sent more than %d messages a second'
                                 % s['max_client_messages_per_second'])
        if not self.authenticated:
            return self._before_auth(message)
        self._handle(message)

    def _handle(self, message):
        before = self.protocol.errors
        self.protocol.incoming(message)
        bad = self.protocol.errors - before
        if bad and not self.budgets.errors.take(bad):
            self._cut_off('sent more than %d bad messages a second'
                          % self.server.settings['max_client_errors_per_second'])

    # ------------------------------------------------------------------- authentication
    def _before_auth(self, message):
        """authenticate: the first op must be a good `auth`; anything else closes."""
        if self.auth_pending:
            if len(self.pending) >= 1000:
                return self._cut_off('sent 1000 messages while its auth was being checked')
            self.pending.append(message)
            return
        try:
            msg = json.loads(message.decode('utf-8') if isinstance(message, bytes) else message)
        except (ValueError, UnicodeDecodeError):
            msg = None
        if not isinstance(msg, dict) or msg.get('op') != 'auth':
            op = msg.get('op') if isinstance(msg, dict) else None
            return self._refuse('its first op was %r, not auth' % (op,))
        self.auth_pending = True
        threading.Thread(target=self._check_auth, args=(msg,), daemon=True,
                         name='rosbridge auth %s' % self.client_id).start()

    def _check_auth(self, msg):
        try:
            ok = bool(self.server.authenticator(msg))
            why = 'wrong, expired or replayed MAC'
        except Exception as e:    # a malformed request or no authenticate service
            ok, why = False, str(e)
        self.loop.add_callback(self._auth_done, ok, why)

    def _auth_done(self, ok, why):
        if self.protocol is None or self.protocol.finished or self.cut:
            return
        self.auth_pending = False
        if not ok:
            return self._refuse(why)
        self.authenticated = True
        logger.info('Client %s has authenticated.' % self.client_id)
        pending, self.pending = self.pending, []
        for message in pending:
            if self.cut:
                break
            self._handle(message)

    def _auth_timeout(self):
        if not self.authenticated and not self.cut and not self.protocol.finished:
            self._refuse('no auth within auth_timeout %g s'
                         % self.server.settings['auth_timeout'])

    def _refuse(self, why):
        self.cut = True
        self.server.counters.add('auth_refused')
        logger.warning('Client %s did not authenticate. Closing connection. (%s)'
                       % (self.client_id, why))
        self._close_with_status('authentication required: %s' % why)

    # ------------------------------------------------------------------------ limits
    def _cut_off(self, why):
        self.cut = True
        self.budgets.penalize()     # its address waits before anything passes again
        self.server.counters.add('clients_cut_off')
        if self.budgets.should_log():
            more, self.budgets.unlogged = self.budgets.unlogged, 0
            logger.warning('[Client %s] cut off: it %s (%s)%s'
                           % (self.client_id, why, self.remote_ip,
                              '; %d more cut-offs of this address since the last line' % more
                              if more else ''))
        self._close_with_status('cut off: the client %s' % why)

    def _close_with_status(self, text):
        """A status message (ahead of anything queued), then the close frame."""
        if self.queue is not None:
            self.queue.close()
        try:
            self.write_message(json.dumps({'op': 'status', 'level': 'error', 'msg': text}))
        except WebSocketClosedError:
            pass
        conn = self.ws_connection       # close() forgets it
        self.close(1008, text[:120])
        # tornado would read (and drop) what the client sends for 5 s more, waiting for its
        # close frame: half a second is enough for the status and the close frame to leave
        if conn is not None:
            self.loop.call_later(0.5, conn.abort)

    def on_close(self):
        if self.protocol is None:
            return
        self.queue.close()
        self.protocol.finish()
        n = self.server.remove(self.client_id)
        if self.queue.dropped:
            logger.warning('[Client %s] dropped %d outgoing messages in all: the client read '
                           'slower than they came (queue bound %d messages / %d bytes, '
                           'at most %d bytes queued)'
                           % (self.client_id, self.queue.dropped, self.queue.max_messages,
                              self.queue.max_bytes, self.queue.high_water))
        logger.info('Client disconnected. %d clients total.' % n)

    # ------------------------------------------------------------------------ outgoing
    def _send_frame(self, data, binary):
        """Any thread: queue a frame; start the writer on the IO loop if it is idle."""
        before = self.queue.dropped
        if self.queue.put(data, binary):
            self.loop.add_callback(self._drain)
        if self.queue.dropped != before:
            self.server.counters.add('queue_dropped', self.queue.dropped - before)
            now = time.monotonic()
            if now - self.last_drop_log > 5.0:
                self.last_drop_log = now
                # the client sees it (if its status level lets warnings through) as the
                # newest frame of its queue
                self.protocol.log('warning', 'outgoing queue full: dropped %d messages so far'
                                  % self.queue.dropped)

    @gen.coroutine
    def _drain(self):
        delay = self.server.settings.get('delay_between_messages') or 0
        while True:
            item = self.queue.get()
            if item is None:
                return
            data, binary = item
            try:
                yield self.write_message(data, binary=binary)
            except WebSocketClosedError:
                self.queue.close()
                self.queue.get()
                return
            if delay > 0:
                yield gen.sleep(delay)
