"""The rospy side of rosbridge: one ROS publisher / subscriber per topic shared by every
client, client-provided services, service calls, and the per-client bookkeeping that lets a
client's departure remove everything it registered.

A topic's publisher stays registered `unregister_timeout` seconds after its last client
unadvertised it (as the original: subscribers that just connected would otherwise miss the
last messages), then goes.
"""
import threading

import rosgraph
import rospy
import rosservice

from rosbridge_library.backend import Backend
from rosbridge_library.internal import ros_loader
from rosbridge_library.internal.outgoing_message import OutgoingMessage


class TypeConflictException(Exception):
    def __init__(self, topic, orig_type, new_type):
        Exception.__init__(self, 'Tried to register topic %s with type %s but it is already '
                           'established with type %s' % (topic, new_type, orig_type))


class _Publisher(object):
    def __init__(self, topic, msg_type, latch, queue_size):
        self.type = msg_type
        self.pub = rospy.Publisher(topic, ros_loader.get_message_class(msg_type), latch=latch,
                                   queue_size=queue_size)
        self.clients = {}       # client id -> registration count
        self.timer = None


class _Subscriber(object):
    def __init__(self, topic, msg_type, callback, queue_size):
        self.type = msg_type
        self.listeners = {}     # client id -> callback
        # a large receive buffer: rospy's default 64 KiB delays large messages (images)
        self.sub = rospy.Subscriber(topic, ros_loader.get_message_class(msg_type), callback,
                                    callback_args=topic, queue_size=queue_size,
                                    buff_size=2 ** 24)


class RosBackend(Backend):
    def __init__(self, unregister_timeout=10.0, subscriber_queue_size=100):
        self.unregister_timeout = float(unregister_timeout)
        self.subscriber_queue_size = subscriber_queue_size
        self.lock = threading.RLock()
        self.publishers = {}    # topic -> _Publisher
        self.subscribers = {}   # topic -> _Subscriber
        self.services = {}      # service -> (client id, srv type, rospy.Service)
        self.service_types = {}  # service -> (provider URI, type) of services probed

    # ------------------------------------------------------------------------ graph
    def now(self):
        t = rospy.get_rostime()
        return t.secs, t.nsecs

    def topic_type(self, topic):
        topic = rosgraph.names.resolve_name(topic, rospy.get_name())
        with self.lock:
            for table in (self.publishers, self.subscribers):
                if topic in table:
                    return table[topic].type
        try:
            # one proxy per call: an xmlrpc ServerProxy breaks when threads share it
            types = dict(rosgraph.Master(rospy.get_name()).getTopicTypes())
        except Exception:
            return None
        t = types.get(topic)
        return t if t and t != '*' else None

    def publisher_type(self, client_id, topic):
        topic = rosgraph.names.resolve_name(topic, rospy.get_name())
        with self.lock:
            p = self.publishers.get(topic)
            return p.type if p is not None and client_id in p.clients else None

    # ------------------------------------------------------------------------ publishers
    def register_publisher(self, client_id, topic, msg_type, latch=False, queue_size=100):
        topic = rosgraph.names.resolve_name(topic, rospy.get_name())
        with self.lock:
            p = self.publishers.get(topic)
            if p is None:
                known = self.topic_type(topic)
                if known is not None and known != msg_type:
                    raise TypeConflictException(topic, known, msg_type)
                p = self.publishers[topic] = _Publisher(topic, msg_type, latch, queue_size)
            elif p.type != msg_type:
                raise TypeConflictException(topic, p.type, msg_type)
            if p.timer is not None:
                p.timer.cancel()
                p.timer = None
            p.clients[client_id] = p.clients.get(client_id, 0) + 1

    def unregister_publisher(self, client_id, topic, all_of_client=False):
        topic = rosgraph.names.resolve_name(topic, rospy.get_name())
        with self.lock:
            p = self.publishers.get(topic)
            if p is None or client_id not in p.clients:
                return
            p.clients[client_id] -= 1
            if all_of_client or p.clients[client_id] <= 0:
                del p.clients[client_id]
            if not p.clients:
                if self.unregister_timeout > 0:
                    p.timer = threading.Timer(self.unregister_timeout, self._expire, (topic, p))
                    p.timer.daemon = True
                    p.timer.start()
                else:
                    self._expire(topic, p)

    def _expire(self, topic, p):
        with self.lock:
            if self.publishers.get(topic) is p and not p.clients:
                del self.publishers[topic]
                p.pub.unregister()

    def publish(self, client_id, topic, message):
        topic = rosgraph.names.resolve_name(topic, rospy.get_name())
        with self.lock:
            p = self.publishers.get(topic)
        if p is None:
            raise Exception('topic %s is not advertised' % topic)
        p.pub.publish(message)

    # ------------------------------------------------------------------------ subscribers
    def subscribe(self, client_id, topic, msg_type, callback):
        topic = rosgraph.names.resolve_name(topic, rospy.get_name())
        with self.lock:
            s = self.subscribers.get(topic)
            if s is None:
                s = self.subscribers[topic] = _Subscriber(topic, msg_type, self._received,
                                                          self.subscriber_queue_size)
            elif s.type != msg_type:
                raise TypeConflictException(topic, s.type, msg_type)
            s.listeners[client_id] = callback

    def _received(self, msg, topic):
        out = OutgoingMessage(msg, self.now())
        with self.lock:
            s = self.subscribers.get(topic)
            listeners = list(s.listeners.values()) if s is not None else []
        for callback in listeners:
            try:
                callback(out)
            except Exception as e:   # one client's failure does not stop the others
                rospy.logerr_throttle(1.0, 'rosbridge: delivering %s failed: %s' % (topic, e))

    def unsubscribe(self, client_id, topic):
        topic = rosgraph.names.resolve_name(topic, rospy.get_name())
        with self.lock:
            s = self.subscribers.get(topic)
            if s is None:
                return
            s.listeners.pop(client_id, None)
            if not s.listeners:
                del self.subscribers[topic]
                s.sub.unregister()

    # ------------------------------------------------------------------------ services
    def service_type(self, service):
        service = rosgraph.names.resolve_name(service, rospy.get_name())
        with self.lock:
            if service in self.services:
                return self.services[service][1]
        # the type is probed with a connection to the service: remembered for as long as the
        # same server (URI) provides it, so a call costs one connection, not two
        try:
            uri = rosgraph.Master(rospy.get_name()).lookupService(service)
        except Exception as e:
            raise Exception('Service %s does not exist (%s)' % (service, e))
        cached = self.service_types.get(service)
        if cached is not None and cached[0] == uri:
            return cached[1]
        try:
            srv_type = rosservice.get_service_type(service)
        except Exception as e:
            raise Exception('Service %s does not exist (%s)' % (service, e))
        if srv_type:
            self.service_types[service] = (uri, srv_type)
        return srv_type

    def call_service(self, service, srv_type, request, timeout=None):
        proxy = rospy.ServiceProxy(service, ros_loader.get_service_class(srv_type))
        try:
            if timeout:
                proxy.wait_for_service(timeout)
            return proxy.call(request)
        finally:
            proxy.close()

    def advertise_service(self, client_id, service, srv_type, handler):
        service = rosgraph.names.resolve_name(service, rospy.get_name())
        with self.lock:
            if service in self.services:
                raise Exception('service %s is already advertised by rosbridge client %s'
                                % (service, self.services[service][0]))
            srv = rospy.Service(service, ros_loader.get_service_class(srv_type), handler)
            self.services[service] = (client_id, srv_type, srv)

    def unadvertise_service(self, client_id, service):
        service = rosgraph.names.resolve_name(service, rospy.get_name())
        with self.lock:
            entry = self.services.get(service)
            if entry is None or entry[0] != client_id:
                return
            del self.services[service]
        entry[2].shutdown('unadvertised by rosbridge client %s' % client_id)

    # ------------------------------------------------------------------------ cleanup
    def finish(self, client_id):
        with self.lock:
            for topic in [t for t, p in self.publishers.items() if client_id in p.clients]:
                self.unregister_publisher(client_id, topic, all_of_client=True)
            for topic in [t for t, s in self.subscribers.items() if client_id in s.listeners]:
                self.unsubscribe(client_id, topic)
            services = [s for s, e in self.services.items() if e[0] == client_id]
        for service in services:
            self.unadvertise_service(client_id, service)

    def counts(self):
        """(publishers, subscribers, services) registered now: for tests and diagnostics."""
        with self.lock:
            return len(self.publishers), len(self.subscribers), len(self.services)
