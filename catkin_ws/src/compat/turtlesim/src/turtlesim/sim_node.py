"""ROS wiring of turtlesim_node: params, global and per-turtle topics/services, the 62.5 Hz loop.

The world (world.py) is guarded by one lock: ROS callbacks (their own threads) only queue
commands or change state under it; the update loop steps the world under it and publishes
the poses afterwards. Names are relative to the node's namespace, so `<group ns=...>` works.
"""
import math
import random
import threading
import time

import rosgraph.names
import rospy
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty, EmptyResponse

from turtlesim.canvas import Canvas
from turtlesim import sprites
from turtlesim.msg import Color, Pose
from turtlesim.srv import (Kill, KillResponse, SetPen, SetPenResponse, Spawn, SpawnResponse,
                           TeleportAbsolute, TeleportAbsoluteResponse, TeleportRelative,
                           TeleportRelativeResponse)
from turtlesim.world import CENTRE, DEFAULT_BACKGROUND, TICK, TurtleError, World

BACKGROUND_PARAMS = ('~background_r', '~background_g', '~background_b')
RESYNC_AFTER = 5      #: ticks of lateness after which the loop drops the missed deadlines


class TurtleHandle:
    """The ROS side of one turtle: its publishers, subscriber and services under `<name>/`."""

    def __init__(self, node, name):
        self.name = name
        self.pose_pub = rospy.Publisher(name + '/pose', Pose, queue_size=1)
        self.color_pub = rospy.Publisher(name + '/color_sensor', Color, queue_size=1)
        self.cmd_sub = rospy.Subscriber(name + '/cmd_vel', Twist, node.cmd_vel_callback,
                                        callback_args=name, queue_size=1)
        self.services = [
            rospy.Service(name + '/set_pen', SetPen, lambda req: node.set_pen_callback(name, req)),
            rospy.Service(name + '/teleport_absolute', TeleportAbsolute,
                          lambda req: node.teleport_absolute_callback(name, req)),
            rospy.Service(name + '/teleport_relative', TeleportRelative,
                          lambda req: node.teleport_relative_callback(name, req)),
        ]

    def shutdown(self):
        self.cmd_sub.unregister()
        self.pose_pub.unregister()
        self.color_pub.unregister()
        for s in self.services:
            s.shutdown('turtle [%s] removed' % self.name)


def read_background():
    """The three ~background_* params as an RGB triple; a bad value is reported and replaced
    by its default."""
    rgb = []
    for param, default in zip(BACKGROUND_PARAMS, DEFAULT_BACKGROUND):
        value = rospy.get_param(param, default)
        if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 255:
            rospy.logerr('Parameter %s = %r is not an integer 0..255; using %d',
                         rospy.resolve_name(param), value, default)
            value = default
        rgb.append(value)
    return tuple(rgb)


class TurtleSimNode:
    """Owns the world, the ROS interfaces and the update loop. `on_update` (optional) is called
    after every tick that changed something (the window uses it to schedule a repaint)."""

    def __init__(self, on_update=None, seed=None):
        self.lock = threading.Lock()            # guards world, canvas, handles
        self._admin = threading.RLock()         # serialises spawn / kill / reset
        self.on_update = on_update
        self.handles = {}
        self.ticks = 0
        for param, default in zip(BACKGROUND_PARAMS, DEFAULT_BACKGROUND):
            if not rospy.has_param(param):
                rospy.set_param(param, default)
        rospy.loginfo('Starting turtlesim with node name %s', rospy.get_name())
        self.canvas = Canvas()
        self.world = World(self.canvas, read_background(), sprites.count(), random.Random(seed))
        self.clear_srv = rospy.Service('clear', Empty, self.clear_callback)
        self.reset_srv = rospy.Service('reset', Empty, self.reset_callback)
        self.spawn_srv = rospy.Service('spawn', Spawn, self.spawn_callback)
        self.kill_srv = rospy.Service('kill', Kill, self.kill_callback)
        self._spawn('', CENTRE, CENTRE, 0.0)

    # --- global services ------------------------------------------------------------------
    def _spawn(self, name, x, y, theta):
        with self._admin:
            if name and not rosgraph.names.is_legal_name(name):
                msg = 'Invalid turtle name [%s]: not a legal ROS name' % name
                rospy.logerr(msg)
                raise rospy.ServiceException(msg)
            with self.lock:
                try:
                    real = self.world.spawn(name, x, y, theta)
                except TurtleError as e:
                    rospy.logerr(str(e))
                    raise rospy.ServiceException(str(e))
            handle = TurtleHandle(self, real)
            with self.lock:
                self.handles[real] = handle
            rospy.loginfo('Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]', real, x, y, theta)
            return real

    def spawn_callback(self, req):
        return SpawnResponse(self._spawn(req.name, req.x, req.y, req.theta))

    def kill_callback(self, req):
        with self._admin:
            with self.lock:
                try:
                    self.world.kill(req.name)
                except TurtleError as e:
                    rospy.logerr(str(e))
                    raise rospy.ServiceException(str(e))
                handle = self.handles.pop(req.name, None)
            if handle:
                handle.shutdown()
        return KillResponse()

    def clear_callback(self, _req=None):
        rospy.loginfo('Clearing turtlesim.')
        background = read_background()
        with self.lock:
            self.world.clear(background)
        self._notify()
        return EmptyResponse()

    def reset_callback(self, _req=None):
        rospy.loginfo('Resetting turtlesim.')
        with self._admin:
            with self.lock:
                # turtle1 comes back at once: keep its topics and services (re-registering
                # the same names from the same node would leave rospy peers reconnecting)
                keep = self.handles.pop('turtle1', None)
                old = list(self.handles.values())
                self.handles.clear()
                self.world.reset()
                t = self.world.turtles['turtle1']
                if keep is not None:
                    self.handles['turtle1'] = keep
            for handle in old:
                handle.shutdown()
            if keep is None:
                handle = TurtleHandle(self, 'turtle1')
                with self.lock:
                    self.handles['turtle1'] = handle
            rospy.loginfo('Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]',
                          t.name, t.x, t.y, t.theta)
        self.clear_callback()
        return EmptyResponse()

    # --- per-turtle callbacks -------------------------------------------------------------
    def _turtle(self, name):
        t = self.world.turtles.get(name)
        if t is None:
            raise rospy.ServiceException('turtle [%s] does not exist' % name)
        return t

    def cmd_vel_callback(self, msg, name):
        v = (msg.linear.x, msg.linear.y, msg.angular.z)
        if not all(math.isfinite(c) for c in v):
            rospy.logwarn_throttle(1.0, 'turtle [%s]: ignoring non-finite cmd_vel %r' % (name, v))
            return
        with self.lock:
            t = self.world.turtles.get(name)
            if t is not None:
                t.command(v[0], v[1], v[2], time.monotonic())

    def set_pen_callback(self, name, req):
        with self.lock:
            self._turtle(name).set_pen(req.r, req.g, req.b, req.width, req.off)
        return SetPenResponse()

    def teleport_absolute_callback(self, name, req):
        with self.lock:
            self._turtle(name).teleport_absolute(req.x, req.y, req.theta)
        return TeleportAbsoluteResponse()

    def teleport_relative_callback(self, name, req):
        with self.lock:
            self._turtle(name).teleport_relative(req.linear, req.angular)
        return TeleportRelativeResponse()

    # --- the loop -------------------------------------------------------------------------
    def _notify(self):
        if self.on_update:
            self.on_update()

    def tick(self):
        """One update: step every turtle by the fixed dt, then publish pose and colour."""
        out = []
        with self.lock:
            hits = self.world.step(TICK, time.monotonic())
            for name, t in self.world.turtles.items():
                handle = self.handles.get(name)
                if handle is None:      # being spawned: its publishers are not up yet
                    continue
                pose = Pose(t.x, t.y, t.theta, t.linear_velocity, t.wz)
                out.append((handle, pose, Color(*self.world.color_under(t))))
        for name, (x, y) in hits:
            rospy.logwarn_throttle(1.0, 'Oh no! I hit the wall! (Clamping from [x=%f, y=%f])'
                                   % (x, y))
        for handle, pose, color in out:
            try:
                handle.pose_pub.publish(pose)
                handle.color_pub.publish(color)
            except rospy.ROSException:
                pass                      # killed between the snapshot and the publish
        self.ticks += 1
        self._notify()

    def run(self, stop):
        """Tick at absolute deadlines t0 + k*TICK until stop() is true (62.5 Hz on average)."""
        next_t = time.monotonic()
        while not stop():
            next_t += TICK
            delay = next_t - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            elif delay < -RESYNC_AFTER * TICK:
                rospy.logwarn_throttle(5.0, 'turtlesim update loop is %.0f ms late; skipping '
                                       'missed ticks' % (-delay * 1000.0))
                next_t = time.monotonic()
            if stop():
                break
            self.tick()

    def snapshot(self):
        """For the window: [(sprite, x, y, theta)] of all turtles (call with self.lock held)."""
        return [(t.sprite, t.x, t.y, t.theta) for t in self.world.turtles.values()]
