"""advertise, unadvertise and publish."""
from rosbridge_library.capabilities.base import Capability
from rosbridge_library.internal import message_conversion, ros_loader


class Advertise(Capability):
    def __init__(self, protocol):
        Capability.__init__(self, protocol)
        self.advertised = {}     # topic -> set of advertisement ids
        protocol.register_operation('advertise', self.advertise)
        protocol.register_operation('unadvertise', self.unadvertise)

    def advertise(self, msg):
        topic = self.arg(msg, 'topic', str)
        msg_type = self.arg(msg, 'type', str)
        latch = self.arg(msg, 'latch', bool, False, False)
        queue_size = self.arg(msg, 'queue_size', int, False, 100)
        if not self.allowed(topic, 'topics_glob'):
            self.protocol.log('warning', 'No advertise permission for topic: %s' % topic,
                              msg.get('id'))
            return
        ros_loader.get_message_class(msg_type)     # unknown type: an error to the client
        self.backend.register_publisher(self.protocol.client_id, topic, msg_type,
                                        latch=latch, queue_size=queue_size)
        self.advertised.setdefault(topic, set()).add(msg.get('id'))

    def unadvertise(self, msg):
        topic = self.arg(msg, 'topic', str)
        if topic not in self.advertised:
            self.protocol.log('warning', 'unadvertise: topic %s is not advertised by this client'
                              % topic, msg.get('id'))
            return
        ids = self.advertised[topic]
        ids.discard(msg.get('id'))
        if msg.get('id') is None or not ids:
            del self.advertised[topic]
            self.backend.unregister_publisher(self.protocol.client_id, topic)

    def finish(self):
        for topic in list(self.advertised):
            self.backend.unregister_publisher(self.protocol.client_id, topic)
        self.advertised.clear()


class Publish(Capability):
    def __init__(self, protocol):
        Capability.__init__(self, protocol)
        self.published = set()
        protocol.register_operation('publish', self.publish)

    def publish(self, msg):
        topic = self.arg(msg, 'topic', str)
        latch = self.arg(msg, 'latch', bool, False, False)
        queue_size = self.arg(msg, 'queue_size', int, False, 100)
        if not self.allowed(topic, 'topics_glob'):
            self.protocol.log('warning', 'No publish permission for topic: %s' % topic,
                              msg.get('id'))
            return
        client = self.protocol.client_id
        msg_type = self.backend.publisher_type(client, topic)
        if msg_type is None:
            msg_type = self.backend.topic_type(topic)
            if msg_type is None:
                raise Exception('Cannot infer topic type for topic %s as it is not yet '
                                'advertised' % topic)
            self.backend.register_publisher(client, topic, msg_type, latch=latch,
                                            queue_size=queue_size)
            self.published.add(topic)
        inst = ros_loader.get_message_instance(msg_type)
        message_conversion.populate_instance(self.arg(msg, 'msg', dict, False, {}), inst,
                                             now=self.backend.now)
        self.backend.publish(client, topic, inst)

    def finish(self):
        for topic in self.published:
            self.backend.unregister_publisher(self.protocol.client_id, topic)
        self.published.clear()
