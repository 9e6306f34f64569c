"""The plugins' ROS endpoints and wall clock, injected through PluginContext (`ctx.io`,
`ctx.wall`): the node passes RosIO() and WallClock(); unit tests without a master get the
defaults MemoryIO() (publishers keep what they publish, no subscribers or services) and may
pass a FakeClock so waits cost no wall time."""
import time

import rospy

# Outgoing queue of the sensor publishers (laser, IMU, odometry, p3d). rospy hands each message
# to a sender thread per subscriber and drops the oldest when its queue is full; at many times
# real time a queue of 1 lost messages whenever that thread waited for the GIL. With this
# queue every message reaches a subscriber that keeps up (bench/sim_rtf counts the stamps).
SENSOR_QUEUE = 100


class MemoryPublisher:
    """Stands in for rospy.Publisher in MemoryIO: `sent` holds the messages, `connections` is
    what get_num_connections() reports (tests set it)."""

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


class MemoryIO:
    """No ROS: publishers in memory, no subscribers, services or parameters."""
    live = False

    def publisher(self, name, data_class, queue_size=1, latch=False):
        return MemoryPublisher(name, data_class, queue_size, latch)

    def subscriber(self, name, data_class, callback, queue_size=1, tcp_nodelay=False):
        return None

    def service(self, name, service_class, handler):
        return None


class RosIO:
    """rospy endpoints of the running node."""
    live = True

    def publisher(self, name, data_class, queue_size=1, latch=False):
        return NoYieldPublisher(name, data_class, queue_size=queue_size, latch=latch)

    def subscriber(self, name, data_class, callback, queue_size=1, tcp_nodelay=False):
        return rospy.Subscriber(name, data_class, callback, queue_size=queue_size,
                                tcp_nodelay=tcp_nodelay)

    def service(self, name, service_class, handler):
        return rospy.Service(name, service_class, handler)


class NoYieldPublisher(rospy.Publisher):
    """rospy.Publisher without the GIL hand-off rospy makes after every message: its
    QueuedConnection.write_data queues the serialized message for the subscriber's sender
    thread, wakes it and then calls time.sleep(0) - a forced thread switch per message and
    subscriber, that at 25x real time costs more than the message. Here the message is queued
    and its sender woken the same way (same queue, same drop-oldest rule, same errors), and the
    sender runs when the simulation thread next releases the GIL: during the next physics step
    group, which runs without it. Messages, order and stamps are unchanged."""

    def publish(self, *args, **kwds):
        impl = self.impl
        if impl is not None:
            for c in impl.connections:
                if 'write_data' not in c.__dict__ and _queued(c):
                    c.write_data = _NoYieldWrite(c)
        return super().publish(*args, **kwds)


def _queued(c):
    from rospy.impl.tcpros_pubsub import QueuedConnection
    return isinstance(c, QueuedConnection) and all(
        hasattr(c, a) for a in ('_lock', '_queue', '_queue_size', '_error',
                                '_cond_data_available'))


class _NoYieldWrite:
    """QueuedConnection.write_data (rospy 1.15/1.16) without its closing time.sleep(0)."""
    __slots__ = ('c',)

    def __init__(self, c):
        self.c = c

    def __call__(self, data):
        c = self.c
        with c._lock:
            if c._error:
                error = c._error
                c._error = None
                raise error
            if c._queue_size > 0 and len(c._queue) == c._queue_size:
                del c._queue[0]
            c._queue.append(data)
            c._cond_data_available.notify()
        return True


class DirectPublisher(rospy.Publisher):
    """A rospy.Publisher for small, frequent messages (/clock) whose publish() writes the
    message to each subscriber's socket itself (one non-blocking send) instead of waking a
    sender thread per subscriber: at 1.0x real time /clock goes out every physics step to
    every node of the graph, and a thread switch (with the GIL) per message and subscriber cost
    more than the messages. A subscriber whose socket buffer is full (a frozen process) loses
    that message, as a full queue drops one; a send that takes only part of a message leaves
    the rest, and every later message, to that subscriber's sender thread (order and framing
    kept). Connections it cannot use this way keep NoYieldPublisher's queued write."""

    def publish(self, *args, **kwds):
        impl = self.impl
        if impl is not None:
            for c in impl.connections:
                if 'write_data' not in c.__dict__ and _queued(c):
                    c.write_data = _DirectWrite(c) if _direct(c) else _NoYieldWrite(c)
        return super().publish(*args, **kwds)


def _direct(c):
    t = getattr(c, '_connection', None)
    return all(hasattr(t, a) for a in ('socket', 'done', 'close'))


class _DirectWrite:
    """write_data of a QueuedConnection that sends in the publishing thread (DirectPublisher)."""
    __slots__ = ('c', 'queued')

    def __init__(self, c):
        self.c = c
        self.queued = None          # _NoYieldWrite after a partial send

    def __call__(self, data):
        import socket
        from rospy.exceptions import TransportInitError, TransportTerminated
        if self.queued is not None:
            return self.queued(data)
        t = self.c._connection
        if t.done:
            raise TransportTerminated('connection closed')
        sock = t.socket
        if sock is None:
            raise TransportInitError('TCPROS transport was not successfully initialized')
        try:
            n = sock.send(data, socket.MSG_DONTWAIT)
        except (BlockingIOError, InterruptedError):
            return True             # the subscriber reads nothing: this message is dropped
        except OSError as e:
            t.close()
            raise TransportTerminated(str(e))
        t.stat_bytes += n
        t.stat_num_msg += 1
        if n < len(data):
            self.queued = _NoYieldWrite(self.c)
            return self.queued(data[n:])
        return True


class WallClock:
    """The wall clock for the few waits that are about wall time (the lockstep timeout)."""

    def now(self):
        return time.monotonic()

    def wait(self, cond, timeout):
        """cond.wait(timeout) on a held threading.Condition."""
        cond.wait(timeout)


class FakeClock:
    """A wall clock for tests: wait() returns at once and advances the time by its timeout
    (after letting other threads run), so a timeout of any length costs no wall time."""

    def __init__(self, t=0.0):
        self.t = t

    def now(self):
        return self.t

    def wait(self, cond, timeout):
        cond.wait(0.001)
        self.t += timeout


class TfBatch:
    """The plugins' shared TF broadcaster (ctx.tf): sendTransform() collects, flush() sends what
    the plugins collected during one step group as one /tf message (tf2_ros's
    TransformBroadcaster publishes one message per call), and nothing while /tf has no
    subscriber. Every transform keeps the stamp its plugin gave it."""

    def __init__(self, io):
        from tf2_msgs.msg import TFMessage
        self._msg = TFMessage
        self._io = io
        # /tf is advertised by the first plugin that broadcasts (asks wanted() or sends), as a
        # gazebo_plugins plugin creates its tf::TransformBroadcaster when it loads: a world
        # without such a plugin advertises no /tf, as Gazebo.
        self._pub = None
        self.pending = []
        self.messages = 0

    def advertised(self):
        return self._pub is not None

    @property
    def pub(self):
        """The /tf publisher (advertised on first use)."""
        return self._publisher()

    def _publisher(self):
        if self._pub is None:
            self._pub = self._io.publisher('/tf', self._msg, queue_size=100)  # tf2_ros's queue
        return self._pub

    def wanted(self):
        """Whether /tf has a subscriber (else plugins need not build their transforms)."""
        return self._publisher().get_num_connections() > 0

    def sendTransform(self, transforms):
        self._publisher()
        if isinstance(transforms, (list, tuple)):
            self.pending.extend(transforms)
        else:
            self.pending.append(transforms)

    def flush(self):
        if not self.pending:
            return
        out, self.pending = self.pending, []
        pub = self._pub
        if pub is not None and pub.get_num_connections() > 0:
            pub.publish(self._msg(transforms=out))
            self.messages += 1

    def shutdown(self):
        close(self._pub)


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
