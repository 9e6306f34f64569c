"""The WebSocket transport (tornado): one Protocol per connection, frames in on the IO loop,
frames out through the client's bounded queue and a writer that awaits each write.

No rospy here: the ROS side arrives as `Server.backend` and the `on_clients_changed` hook.
"""
import logging
import threading
import time

from tornado import gen
from tornado.ioloop import IOLoop
from tornado.websocket import WebSocketClosedError, WebSocketHandler

from rosbridge_library.protocol import Protocol
from rosbridge_server.client_queue import ClientQueue

logger = logging.getLogger('rosout')


class Server(object):
    """State shared by the connections of one server."""

    def __init__(self, backend, settings, protocol_settings, on_clients_changed=None):
        self.backend = backend
        self.settings = settings
        self.protocol_settings = protocol_settings
        self.on_clients_changed = on_clients_changed or (lambda clients: None)
        self.lock = threading.Lock()
        self.next_id = 0
        self.clients = {}          # client id -> RosbridgeWebSocket
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

    def check_origin(self, origin):
        return True      # the course page is served from another port

    def get_compression_options(self):
        return {} if self.server.settings.get('use_compression') else None

    def open(self):
        s = self.server.settings
        self.loop = IOLoop.current()
        self.remote_ip = self.request.remote_ip or ''
        self.connected_at = time.time()
        self.queue = ClientQueue(s['max_client_queue_messages'], s['max_client_queue_bytes'])
        self.client_id, n = self.server.add(self)
        self.protocol = Protocol(self.client_id, self.server.backend, self._send_frame,
                                 self.server.protocol_settings)
        self.set_nodelay(True)
        logger.info('Client connected.  %d clients total.' % n)

    def on_message(self, message):
        self.protocol.incoming(message)

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
            now = time.monotonic()
            if now - self.last_drop_log > 5.0:
                self.last_drop_log = now
                logger.warning('[Client %s] outgoing queue full: dropped %d messages so far'
                               % (self.client_id, self.queue.dropped))

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
