"""The interface between the protocol and ROS. `internal/ros_backend.RosBackend` implements it
with rospy for the server; tests use an in-memory one. One backend serves every client: it
shares one ROS publisher / subscriber per topic between them and owns the per-client
bookkeeping, so `finish(client_id)` leaves nothing of a client behind."""


class Backend(object):
    def now(self):
        """(secs, nsecs) of the ROS clock."""
        raise NotImplementedError

    def topic_type(self, topic):
        """Type of a topic known to the graph (or advertised here), or None."""
        raise NotImplementedError

    def publisher_type(self, client_id, topic):
        """Type under which this client publishes on topic, or None."""
        raise NotImplementedError

    def register_publisher(self, client_id, topic, msg_type, latch=False, queue_size=100):
        raise NotImplementedError

    def unregister_publisher(self, client_id, topic):
        raise NotImplementedError

    def publish(self, client_id, topic, message):
        raise NotImplementedError

    def subscribe(self, client_id, topic, msg_type, callback):
        """callback(OutgoingMessage) for every message on topic, until unsubscribe."""
        raise NotImplementedError

    def unsubscribe(self, client_id, topic):
        raise NotImplementedError

    def service_type(self, service):
        raise NotImplementedError

    def call_service(self, service, srv_type, request, timeout=None):
        raise NotImplementedError

    def advertise_service(self, client_id, service, srv_type, handler):
        """handler(request) -> response, called on a ROS thread."""
        raise NotImplementedError

    def unadvertise_service(self, client_id, service):
        raise NotImplementedError

    def finish(self, client_id):
        raise NotImplementedError
