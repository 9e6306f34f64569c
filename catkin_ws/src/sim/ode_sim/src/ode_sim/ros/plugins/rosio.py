"""ROS endpoints of the built-in plugins. Publishers, subscribers and services are created only
when rospy is initialised (the sim node); otherwise (unit tests without a master) `publisher()`
returns a MemoryPublisher that keeps what was published, and subscribers/services are None."""
import rospy


class MemoryPublisher:
    """Stands in for rospy.Publisher when no node is initialised: `sent` holds the messages,
    `connections` is what get_num_connections() reports (tests set it)."""

    DEFAULT_CONNECTIONS = 1

    def __init__(self, name, data_class=None, queue_size=None, latch=False):
        self.name = name
        self.data_class = data_class
        self.queue_size = queue_size
        self.latch = latch
        self.sent = []
        self.connections = self.DEFAULT_CONNECTIONS
        self.unregistered = False

    def publish(self, msg):
        if self.data_class is not None:
            assert isinstance(msg, self.data_class), (self.name, type(msg))
        self.sent.append(msg)

    def get_num_connections(self):
        return self.connections

    def unregister(self):
        self.unregistered = True


def ros_up():
    return rospy.core.is_initialized()


def publisher(name, data_class, queue_size=1, latch=False):
    if ros_up():
        return rospy.Publisher(name, data_class, queue_size=queue_size, latch=latch)
    return MemoryPublisher(name, data_class, queue_size, latch)


def subscriber(name, data_class, callback, queue_size=1, tcp_nodelay=False):
    if ros_up():
        return rospy.Subscriber(name, data_class, callback, queue_size=queue_size,
                                tcp_nodelay=tcp_nodelay)
    return None


def service(name, service_class, handler):
    if ros_up():
        return rospy.Service(name, service_class, handler)
    return None


def close(*handles):
    for h in handles:
        if h is None:
            continue
        try:
            if hasattr(h, 'unregister'):
                h.unregister()
            elif hasattr(h, 'shutdown'):
                h.shutdown()
        except Exception:       # shutting down anyway
            pass


def subscribed(pub):
    return pub is not None and pub.get_num_connections() > 0
