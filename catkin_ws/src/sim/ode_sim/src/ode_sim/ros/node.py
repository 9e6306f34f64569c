"""The simulator process: world + robots + plugins, paced as Gazebo, with the /gazebo ROS API.

The simulation thread steps the physics; rospy threads serve /gazebo/* services, which take
`self.lock` around every change of the world. See gazebo_api.py for the services.
"""
import threading
import time

import rospy
from rosgraph_msgs.msg import Clock

from ode_sim.ros import plugins as plugin_registry
from ode_sim.description.model import ModelError
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.plugins.base import PluginContext
from ode_sim.ros.plugins.rosio import FanoutPublisher, RosIO, TfBatch, WallClock
from ode_sim.ros.stepping import MAX_GROUP, StepLoop  # noqa: F401 (MAX_GROUP: tests)


class Spawner:
    """Turns a Model description into a simulated model with its plugins."""

    def __init__(self, node):
        self.node = node

    def plugins_for(self, sim_model, desc):
        """Instantiate the model's and its sensors' plugins; unknown ones warn and are skipped."""
        ctx = self.node.ctx
        out = []
        tags = [(p, None) for p in desc.plugins]
        for link in desc.links:
            for sensor in link.sensors:
                for p in sensor.plugins:
                    tags.append((p, sensor))
        for p, sensor in tags:
            cls = plugin_registry.lookup(p.filename)
            if cls is None:
                rospy.logwarn("ode_sim: %s: model '%s': unknown plugin '%s' (name '%s') ignored; "
                              "known plugins: %s" % (p.source or desc.source, desc.name,
                                                     p.filename, p.name,
                                                     ', '.join(plugin_registry.known())))
                continue
            out.append(cls(ctx, sim_model, p, sensor))
        return out


class Pacer:
    """Gazebo's pacing: with `real_time_update_rate` R > 0, step k after a (re)start is due at
    wall0 + k / R, so sim time runs at max_step_size x R per wall second (1.0 for the defaults);
    R = 0 never waits (as fast as possible). A simulator that falls more than `behind` seconds
    late (a slow or loaded machine) restarts the count instead of racing to catch up.
    The clock and sleep are injectable so the policy is tested without the wall clock."""

    def __init__(self, clock=time.monotonic, sleep=time.sleep, behind=0.5, min_sleep=0.002):
        self.clock, self.sleep = clock, sleep
        self.behind, self.min_sleep = behind, min_sleep
        self.rate, self.wall0, self.steps0 = 0.0, 0.0, 0
        self.slept = 0.0        # wall seconds spent waiting since construction
        self.resyncs = 0

    def restart(self, rate, steps):
        self.rate, self.wall0, self.steps0 = rate, self.clock(), steps

    def after_step(self, steps):
        """Wait until step `steps` is due; False when the count must restart (fell behind)."""
        if self.rate <= 0:
            return True
        ahead = self.wall0 + (steps - self.steps0) / self.rate - self.clock()
        if ahead > self.min_sleep:
            self.sleep(ahead)
            self.slept += ahead
        elif ahead < -self.behind:
            self.resyncs += 1
            return False
        return True


class SimNode(StepLoop):
    """The stepping policy of StepLoop (group_size, step_once) with models, pacing and /clock."""

    def __init__(self, world, paused=False, lockstep=False, verbose=False):
        io = RosIO()
        # one /tf message per step group (step_once)
        super().__init__(PhysicsWorld(world.physics, world.gravity), TfBatch(io))
        self.world = world
        self.paused = paused
        self.verbose = verbose
        self.rate = world.physics.real_time_update_rate
        self.plugins = {}           # model name -> [Plugin]
        self.ctx = PluginContext(self.physics, world, lockstep=lockstep, tf=self.tf, io=io,
                                 wall=WallClock())
        self.spawner = Spawner(self)
        # sent to the subscribers' sockets by the compiled core's thread (rosio.FanoutPublisher):
        # /clock goes to every node every step, and costs this thread no system call
        self.clock_pub = FanoutPublisher('/clock', Clock, queue_size=10)
        freq = float(rospy.get_param('gazebo/pub_clock_frequency', 0) or 0)
        self.clock_period = 1.0 / freq if freq > 0 else 0.0
        self._last_clock = -1.0
        self._last_clock_wall = 0.0
        self._own_clock = self._stop_clock_subscription()
        self._stop = threading.Event()
        self._resync = True
        for m in world.models:
            self.add_model(m)
        for w in world.warnings:
            rospy.logwarn('ode_sim: %s' % w)

    # ----------------------------------------------------------------- models
    def add_model(self, desc):
        """Add a model and start its plugins (under the lock). Raises ModelError."""
        with self.lock:
            try:
                sim_model = self.physics.add_model(desc)
            finally:
                for w in desc.warnings:
                    rospy.logwarn('ode_sim: %s' % w)
            try:
                plugins = self.spawner.plugins_for(sim_model, desc)
            except Exception as e:
                self.physics.remove_model(desc.name)
                if isinstance(e, ModelError):
                    raise
                raise ModelError("model '%s': a plugin failed to load: %s" % (desc.name, e))
            self.plugins[desc.name] = plugins
            self._rebuild_hooks()
            return sim_model

    def remove_model(self, name):
        with self.lock:
            for p in self.plugins.pop(name, []):
                try:
                    p.shutdown()
                except Exception as e:  # a failing plugin must not keep the model alive
                    rospy.logwarn('ode_sim: plugin shutdown of model %s: %s' % (name, e))
            self._rebuild_hooks()
            return self.physics.remove_model(name)

    def _rebuild_hooks(self):
        self.set_plugins([p for ps in self.plugins.values() for p in ps])

    # ----------------------------------------------------------------- control
    def pause(self):
        self.paused = True

    def unpause(self):
        self.paused = False
        self._resync = True

    def reset(self, time_too):
        with self.lock:
            self.physics.reset_world()
            if time_too:
                self.physics.reset_time()
                self._last_clock = -1.0
            for ps in self.plugins.values():
                for p in ps:
                    p.reset()
            self._resync = True
            self.publish_clock(force=True)

    # ----------------------------------------------------------------- loop
    @staticmethod
    def _stop_clock_subscription():
        """With /use_sim_time, rospy.init_node subscribed this process to /clock: the node
        would receive (a sender and a receiver thread, deserialisation under the GIL) every
        /clock message it publishes. Gazebo does not listen to its own clock; here the
        subscription is dropped and publish_clock() sets rospy's time directly, at the same
        moments (True then)."""
        from rospy.impl import simtime
        sub = getattr(simtime, '_clock_sub', None)
        if sub is None:
            return False
        sub.unregister()
        simtime._clock_sub = None
        return True

    def publish_clock(self, force=False):
        t = self.physics.time
        listened = self.clock_pub.get_num_connections() > 0
        if not force and not listened and not self._own_clock:
            return                      # nobody listens: no serialisation, no GIL hand-off
        if not force:
            if self.clock_period > 0:
                if self._last_clock >= 0 and t - self._last_clock < self.clock_period - 1e-9:
                    return
            else:
                # every step, but not more often than 1 kHz of wall time (fast mode)
                now = time.monotonic()
                if now - self._last_clock_wall < 0.001:
                    return
                self._last_clock_wall = now
        self._last_clock = t
        stamp = rospy.Time.from_sec(t)
        if self._own_clock:             # what the node's own /clock subscription did
            rospy.rostime._set_rostime(stamp)
        if force or listened:
            self.clock_pub.publish(Clock(clock=stamp))

    def spin(self):
        """Run until rospy shuts down: step, pace, publish."""
        pacer = Pacer()
        self.publish_clock(force=True)
        while not rospy.is_shutdown() and not self._stop.is_set():
            if self.paused:
                if self.paused_hooks:
                    with self.lock:
                        for hook in self.paused_hooks:
                            hook()
                time.sleep(0.005)
                self._resync = True
                continue
            if self._resync:
                self._resync = False
                self.rate = self.world.physics.real_time_update_rate
                pacer.restart(self.rate, self.physics.steps)
            self.step_once(self.group_size() if self.rate <= 0 else 1)
            if not pacer.after_step(self.physics.steps):
                self._resync = True     # fell far behind (slow machine): do not catch up
        for ps in self.plugins.values():
            for p in ps:
                try:
                    p.shutdown()
                except Exception:
                    pass

    def stop(self):
        self._stop.set()
