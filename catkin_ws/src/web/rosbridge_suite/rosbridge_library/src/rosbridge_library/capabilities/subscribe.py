"""subscribe and unsubscribe, with throttle_rate, queue_length, fragment_size, compression.

A client has one ROS subscription per topic however many `subscribe`s (with different ids) it
sent; as the original, messages go out at the lowest throttle_rate, with the lowest
fragment_size and the highest queue_length of them.
- throttle_rate 0, queue_length 0: every message goes out as it arrives;
- throttle_rate > 0, queue_length 0: a message arriving sooner than throttle_rate ms after the
  last one sent is dropped;
- queue_length > 0: a queue of that length (the oldest dropped when full) drained by a thread,
  at most one message per throttle_rate ms.
"""
import collections
import threading
import time

from rosbridge_library.capabilities.base import Capability, InvalidArgumentException
from rosbridge_library.internal import ros_loader

COMPRESSIONS = ('none', 'png', 'cbor', 'cbor-raw')


class Subscription(object):
    """One client's subscription to one topic."""

    def __init__(self, protocol, topic):
        self.protocol = protocol
        self.topic = topic
        self.specs = {}             # subscription id -> dict of options
        self.lock = threading.Condition()
        self.queue = None
        self.thread = None
        self.last_sent = 0.0
        self.closed = False
        self.sent = 0
        self.dropped = 0
        self._update()

    def add(self, sid, spec):
        with self.lock:
            self.specs[sid] = spec
            self._update()

    def remove(self, sid):
        with self.lock:
            self.specs.pop(sid, None)
            self._update()
            return not self.specs

    def _update(self):
        specs = list(self.specs.values()) or [{}]
        self.throttle_rate = min(s.get('throttle_rate', 0) for s in specs)
        self.queue_length = max(s.get('queue_length', 0) for s in specs)
        sizes = [s['fragment_size'] for s in specs if s.get('fragment_size')]
        self.fragment_size = min(sizes) if sizes else None
        self.compression = specs[-1].get('compression', 'none')
        if self.queue_length > 0:
            old = list(self.queue or ())
            self.queue = collections.deque(old[-self.queue_length:], maxlen=self.queue_length)
            if self.thread is None:
                self.thread = threading.Thread(target=self._drain, daemon=True,
                                               name='rosbridge queue %s' % self.topic)
                self.thread.start()
            self.lock.notify_all()

    def on_message(self, outgoing):
        """Called by the backend (a ROS callback thread) with an OutgoingMessage."""
        with self.lock:
            if self.closed:
                return
            if self.queue_length > 0:
                if len(self.queue) == self.queue.maxlen:
                    self.dropped += 1
                self.queue.append(outgoing)
                self.lock.notify()
                return
            if self.throttle_rate > 0:
                now = time.monotonic()
                if (now - self.last_sent) * 1000.0 < self.throttle_rate:
                    self.dropped += 1
                    return
                self.last_sent = now
        self._send(outgoing)

    def _send(self, outgoing):
        self.sent += 1
        self.protocol.send_frames(outgoing.publish_frames(self.topic, self.compression,
                                                          self.fragment_size))

    def _drain(self):
        while True:
            with self.lock:
                while not self.closed and not self.queue:
                    self.lock.wait()
                if self.closed:
                    return
                outgoing = self.queue.popleft()
                rate = self.throttle_rate
            self._send(outgoing)
            if rate > 0:
                with self.lock:
                    self.lock.wait_for(lambda: self.closed, rate / 1000.0)

    def close(self):
        with self.lock:
            self.closed = True
            self.lock.notify_all()


class Subscribe(Capability):
    def __init__(self, protocol):
        Capability.__init__(self, protocol)
        self.subscriptions = {}     # topic -> Subscription
        protocol.register_operation('subscribe', self.subscribe)
        protocol.register_operation('unsubscribe', self.unsubscribe)

    def subscribe(self, msg):
        topic = self.arg(msg, 'topic', str)
        msg_type = self.arg(msg, 'type', str, False)
        spec = {'throttle_rate': self.arg(msg, 'throttle_rate', int, False, 0),
                'queue_length': self.arg(msg, 'queue_length', int, False, 0),
                'fragment_size': self.arg(msg, 'fragment_size', int, False, None),
                'compression': self.arg(msg, 'compression', str, False, 'none')}
        if spec['compression'] not in COMPRESSIONS:
            raise InvalidArgumentException('Expected field compression to be one of %s. '
                                           'Invalid value: %s' % (list(COMPRESSIONS),
                                                                  spec['compression']))
        if spec['throttle_rate'] < 0 or spec['queue_length'] < 0:
            raise InvalidArgumentException('throttle_rate and queue_length must not be '
                                           'negative')
        if not self.allowed(topic, 'topics_glob'):
            self.protocol.log('warning', 'No subscription permission for topic: %s' % topic,
                              msg.get('id'))
            return
        known = self.backend.topic_type(topic)
        if msg_type is None:
            if known is None:
                raise Exception('Cannot infer topic type for topic %s as it is not yet '
                                'advertised' % topic)
            msg_type = known
        elif known is not None and known != msg_type:
            raise Exception('Tried to subscribe to topic %s with type %s, but the topic has '
                            'type %s' % (topic, msg_type, known))
        ros_loader.get_message_class(msg_type)    # unknown type: an error to the client
        sid = msg.get('id')
        sub = self.subscriptions.get(topic)
        limit = self.protocol.settings.get('max_subscriptions')
        if sub is None and limit and len(self.subscriptions) >= limit:
            self.protocol.count('subscriptions_refused')
            raise Exception('this client already subscribes to %d topics, the most '
                            'max_client_subscriptions allows: %s refused'
                            % (len(self.subscriptions), topic))
        if sub is None:
            sub = Subscription(self.protocol, topic)
            sub.add(sid, spec)
            self.backend.subscribe(self.protocol.client_id, topic, msg_type, sub.on_message)
            self.subscriptions[topic] = sub
        else:
            sub.add(sid, spec)

    def unsubscribe(self, msg):
        topic = self.arg(msg, 'topic', str)
        sub = self.subscriptions.get(topic)
        if sub is None:
            self.protocol.log('warning', 'unsubscribe: not subscribed to topic %s' % topic,
                              msg.get('id'))
            return
        sid = msg.get('id')
        if sid is None or sid not in sub.specs or sub.remove(sid):
            self._drop(topic)

    def _drop(self, topic):
        sub = self.subscriptions.pop(topic)
        sub.close()
        self.backend.unsubscribe(self.protocol.client_id, topic)

    def finish(self):
        for topic in list(self.subscriptions):
            self._drop(topic)
