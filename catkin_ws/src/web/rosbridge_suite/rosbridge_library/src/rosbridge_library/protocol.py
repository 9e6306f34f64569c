"""One client's rosbridge v2 protocol session: parses incoming frames, dispatches each `op`
to its capability, and turns every failure into a `status` message to that client (and a
log line in the original's format, "[Client N] [id: X] op: reason").

No ROS imports: the ROS side is a backend object (see backend.py); the transport hands in
frames with `incoming()` and receives frames through the `send_frame(data, binary)` callable.
"""
import json
import logging

from rosbridge_library.internal import wire

LEVELS = {'none': 0, 'error': 1, 'warning': 2, 'info': 3}
_ALIASES = {'err': 'error', 'warn': 'warning', 'information': 'info'}

DEFAULT_SETTINGS = {
    'fragment_timeout': 600,
    'delay_between_messages': 0,
    'max_message_size': None,
    'topics_glob': [],
    'services_glob': [],
    'params_glob': [],
    'status_level': 'error',
    'service_call_timeout': None,
    'max_subscriptions': None,      # ours: topics one client may subscribe to at once
    'count': None,                  # ours: count(name) when a limit is hit (the server's)
}

logger = logging.getLogger('rosout')   # rospy routes this logger to /rosout and the console


class ProtocolError(Exception):
    """A request the client got wrong; the text goes to the client in a status message."""


class Protocol(object):
    def __init__(self, client_id, backend, send_frame, settings=None):
        self.client_id = client_id
        self.backend = backend
        self.send_frame = send_frame
        self.settings = dict(DEFAULT_SETTINGS)
        self.settings.update(settings or {})
        self.status_level = self.settings['status_level']
        self.operations = {}
        self.capabilities = []
        self.finished = False
        self.errors = 0             # error statuses caused by this client (the transport's
        # garbage budget reads it)
        self.count = self.settings.get('count') or (lambda name, n=1: None)
        from rosbridge_library.capabilities import (defragmentation, services, subscribe,
                                                    topics)
        for cap in (topics.Advertise, topics.Publish, subscribe.Subscribe,
                    services.CallService, services.AdvertiseService,
                    defragmentation.Defragment):
            self.capabilities.append(cap(self))
        self.register_operation('set_level', self.set_level)
        self.register_operation('auth', self.auth)

    # -------------------------------------------------------------------------- incoming
    def register_operation(self, op, handler):
        self.operations[op] = handler

    def incoming(self, data):
        """One frame from the client (str: JSON text; bytes: a binary frame)."""
        limit = self.settings.get('max_message_size')
        if limit and len(data) > limit:
            self.count('messages_too_large')
            self.log('error', 'Received a message of %d bytes, more than max_message_size %d: '
                     'dropped' % (len(data), limit))
            return
        try:
            if isinstance(data, (bytes, bytearray)):
                data = data.decode('utf-8')
            msg = json.loads(data)
        except (ValueError, UnicodeDecodeError) as e:
            self.log('error', 'Unable to deserialize message from client: %s. Exception was: %s'
                     % (_shorten(data), e))
            return
        self.dispatch(msg, data)

    def dispatch(self, msg, text=None):
        if not isinstance(msg, dict):
            self.log('error', 'Received a message that is not a JSON object: %s'
                     % _shorten(text if text is not None else msg))
            return
        mid = msg.get('id')
        if 'op' not in msg:
            if 'receiver' in msg:
                self.log('error', 'Received a rosbridge v1.0 message.  Please refer to '
                         'rosbridge.org for the correct format of rosbridge v2.0 messages.  '
                         'Original message was: %s' % _shorten(text or msg))
            else:
                self.log('error', "Received a message without an op.  All messages require 'op' "
                         'field with value one of: %s.  Original message was: %s'
                         % (sorted(self.operations), _shorten(text or msg)), mid)
            return
        op = msg['op']
        handler = self.operations.get(op) if isinstance(op, str) else None
        if handler is None:
            self.log('error', 'Unknown operation: %s.  Allowed operations: %s'
                     % (op, sorted(self.operations)), mid)
            return
        try:
            handler(msg)
        except Exception as exc:   # any failure of one request reaches that client only
            self.log('error', '%s: %s' % (op, exc), mid)

    # -------------------------------------------------------------------------- outgoing
    def send(self, message, compression='none', fragment_size=None):
        """Send a protocol message (dict) to the client."""
        self.send_frames(wire.frames(message, compression, fragment_size, message.get('id')))

    def send_frames(self, frames):
        if self.finished:
            return
        for data, binary in frames:
            self.send_frame(data, binary)

    def auth(self, msg):
        """`auth` reaches the protocol only where the transport does not require it (or after
        the client authenticated): nothing to do."""
        self.log('info', 'auth: this connection needs no (more) authentication', msg.get('id'))

    def set_level(self, msg):
        level = _ALIASES.get(msg.get('level'), msg.get('level'))
        if level not in LEVELS:
            raise ProtocolError('unknown status level %r, expected one of %s'
                                % (msg.get('level'), sorted(LEVELS)))
        self.status_level = level

    def log(self, level, message, mid=None):
        """Log as the original ("[Client N] [id: X] text") and send a `status` message if the
        client's level lets it through."""
        level = _ALIASES.get(level, level)
        if level == 'error':
            self.errors += 1
        if mid is not None:
            line = '[Client %s] [id: %s] %s' % (self.client_id, mid, message)
        else:
            line = '[Client %s] %s' % (self.client_id, message)
        {'error': logger.error, 'warning': logger.warning,
         'info': logger.info}.get(level, logger.debug)(line)
        if LEVELS.get(level, 3) <= LEVELS[self.status_level] and LEVELS[self.status_level] > 0:
            status = {'op': 'status', 'level': level, 'msg': message}
            if mid is not None:
                status['id'] = mid
            self.send(status)

    def finish(self):
        """The client went away: drop every publisher, subscriber and service it owned."""
        self.finished = True
        for cap in self.capabilities:
            try:
                cap.finish()
            except Exception as e:   # cleanup goes on for the other capabilities
                logger.error('[Client %s] cleanup of %s failed: %s'
                             % (self.client_id, type(cap).__name__, e))
        self.backend.finish(self.client_id)


def _shorten(text, n=200):
    text = text if isinstance(text, str) else repr(text)
    return text if len(text) <= n else text[:n] + '... (%d characters)' % len(text)
