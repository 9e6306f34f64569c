"""The plugins' ROS endpoints and wall clock, injected through PluginContext (`ctx.io`,
`ctx.wall`): the node passes RosIO() and WallClock(); unit tests without a master get the
defaults MemoryIO() (publishers keep what they publish, no subscribers or services) and may
pass a FakeClock so waits cost no wall time."""
import threading
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


class FanoutPublisher(rospy.Publisher):
    """A rospy.Publisher for a small, frequent message (/clock) whose frames go to every
    subscriber's socket from a thread of the compiled core (engine/core/fanout.h), not from the
    publishing thread: at 1.0x real time /clock goes out every physics step to every node of the
    graph, and as fast as the machine allows at real_time_update_rate 0, and one send per node
    cost the simulation thread as much as the physics. publish() serializes the message as
    rospy does and hands the frame over (no system call while the thread is busy sending); the
    thread sends the newest frame (a subscriber never gets an older time after a newer one), a
    full socket misses it whole, a frame sent in part is completed, and a failed socket ends
    its connection as a failed rospy write does. Connections it cannot send to this way (no
    socket) keep NoYieldPublisher's queued write."""

    def __init__(self, name, data_class, queue_size=10):
        from ode_sim.engine._core import Fanout
        super().__init__(name, data_class, queue_size=queue_size)
        self._fan = Fanout()
        self._handles = {}          # QueuedConnection -> the fan-out's handle
        self._dead = set()          # handles whose socket failed (connection still listed)
        self._seen = None           # impl.connections as last synchronised
        self._sync_lock = threading.Lock()      # publish() runs in the service threads too
        self.handed = None          # the frame last handed over

    def publish(self, *args, **kwds):
        impl = self.impl
        if impl is not None:
            if impl.connections is not self._seen:      # rospy replaces the list on a change
                with self._sync_lock:
                    self._sync(impl.connections)
            self._dead.update(self._fan.take_dead())
        return super().publish(*args, **kwds)

    def _sync(self, conns):
        self._seen = conns
        for c in conns:
            if 'write_data' in c.__dict__ or not _queued(c):
                continue
            sock = getattr(getattr(c, '_connection', None), 'socket', None)
            try:
                handle = self._fan.add(sock.fileno()) if _direct(c) else None
            except (AttributeError, OSError):
                handle = None
            if handle is None:
                c.write_data = _NoYieldWrite(c)
            else:
                self._handles[c] = handle
                c.write_data = _FanoutWrite(self, c, handle)
        for c in [c for c in self._handles if c not in conns]:
            self._fan.remove(self._handles.pop(c))

    def unregister(self):
        super().unregister()
        self._fan.close()


class _FanoutWrite:
    """write_data of a QueuedConnection whose frames FanoutPublisher's thread sends: the first
    of a publish's connections hands the frame over, the others only count it (rospy writes
    one publish's bytes object to every connection, under the publisher's lock)."""
    __slots__ = ('pub', 'c', 'handle')

    def __init__(self, pub, c, handle):
        self.pub, self.c, self.handle = pub, c, handle

    def __call__(self, data):
        from rospy.exceptions import TransportTerminated
        pub, t = self.pub, self.c._connection
        if self.handle in pub._dead or t.done:
            pub._dead.discard(self.handle)
            t.close()
            raise TransportTerminated('connection closed')
        if data is not pub.handed:
            pub._fan.publish(data)
            pub.handed = data
        t.stat_bytes += len(data)
        t.stat_num_msg += 1
        return True


def _direct(c):
    t = getattr(c, '_connection', None)
    return all(hasattr(t, a) for a in ('socket', 'done', 'close'))


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
