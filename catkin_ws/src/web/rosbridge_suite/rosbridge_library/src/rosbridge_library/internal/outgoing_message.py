"""One received ROS message on its way to many clients: converted and serialized once per
encoding, however many clients subscribe (the publish frame is the same for all of them)."""
import threading

from rosbridge_library.internal import message_conversion, wire


class OutgoingMessage(object):
    def __init__(self, msg, stamp=(0, 0)):
        self.msg = msg
        self.stamp = stamp          # (secs, nsecs) of reception, for cbor-raw
        self._lock = threading.RLock()
        self._cache = {}

    def _cached(self, key, make):
        with self._lock:
            if key not in self._cache:
                self._cache[key] = make()
            return self._cache[key]

    def values(self):
        """The message as JSON values (dict)."""
        return self._cached('json', lambda: message_conversion.extract_values(self.msg))

    def binary_values(self):
        return self._cached('cbor', lambda: message_conversion.extract_values(self.msg, True))

    def raw(self):
        def make():
            import io
            buf = io.BytesIO()
            self.msg.serialize(buf)
            return buf.getvalue()
        return self._cached('raw', make)

    def publish_message(self, topic, compression='none'):
        """The `publish` protocol message for this topic and compression (a dict)."""
        if compression == 'cbor':
            body = self.binary_values()
        elif compression == 'cbor-raw':
            body = {'secs': self.stamp[0], 'nsecs': self.stamp[1], 'bytes': self.raw()}
        else:
            body = self.values()
        return {'op': 'publish', 'topic': topic, 'msg': body}

    def publish_frames(self, topic, compression='none', fragment_size=None):
        """The frames of the publish message; shared by every client with the same settings."""
        return self._cached(('frames', topic, compression, fragment_size), lambda: wire.frames(
            self.publish_message(topic, compression), compression, fragment_size))
