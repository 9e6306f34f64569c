"""The simulation thread's stepping policy, without ROS: which plugins run before and after a
physics step, how many steps one call into the engine may take (group_size) and what runs after
it (step_once). SimNode (node.py) is a StepLoop with ROS pacing and /clock around it;
bench/sim_scale runs a StepLoop on in-memory publishers, so it measures what the node does."""
import threading

from ode_sim.ros.plugins.base import NO_WORK, Plugin

MAX_GROUP = 50      # steps per call at most when running as fast as possible (50 ms at 1 kHz)


class StepLoop:
    """physics: PhysicsWorld; tf: the plugins' shared rosio.TfBatch (flushed once per group)."""

    def __init__(self, physics, tf, lock=None):
        self.physics = physics
        self.tf = tf
        self.lock = lock if lock is not None else threading.RLock()
        self._pre = []              # plugins overriding before_step
        self._post = []             # plugins overriding update
        self._limits = []           # their next_update
        self.before_step_hooks = []  # callables run before each step (forces of the /gazebo API)
        self.step_hooks = []        # callables run after each step (model_states publisher ...)
        self.paused_hooks = []      # callables run (under the lock) while paused, every 5 ms
        self.group_limits = []      # callables: when a hook next has work (see group_size)

    def set_plugins(self, plugins):
        """The plugins that run around every step (all models' plugins, in spawn order)."""
        self._pre = [p for p in plugins if type(p).before_step is not Plugin.before_step]
        self._post = [p for p in plugins if type(p).update is not Plugin.update]
        self._limits = [p.next_update for p in self._pre + self._post]

    def group_size(self):
        """How many steps the node may take in one call when running as fast as possible: up
        to the first time a plugin or hook has work (next_update()), at most MAX_GROUP; 1
        when one of them must run after every step. Plugins then run at the very steps they
        would run at one step at a time, so stamps and rates do not change."""
        n = MAX_GROUP
        pw = self.physics
        t = pw.time
        for f in self._limits + self.group_limits:
            nu = f()
            if nu is None:
                return 1
            if nu == NO_WORK:
                continue
            if t + 1e-9 >= nu:
                return 1
            # the first k with time_after(k) + 1e-9 >= nu, as Plugin.due() decides
            k = max(1, min(n, int((nu - t) / pw.dt) - 1))
            while k < n and pw.time_after(k) + 1e-9 < nu:
                k += 1
            n = k
            if n == 1:
                return 1
        return n

    def step_once(self, n=1):
        """before_step of the plugins, the before-step hooks, n physics steps in one call, the
        plugins' update(), the step hooks, one /tf message, then publish_clock()."""
        for p in self._pre:
            p.before_step()
        with self.lock:
            for hook in self.before_step_hooks:
                hook()
            self.physics.step(n)
            for p in self._post:
                p.update()
            for hook in self.step_hooks:
                hook()
            self.tf.flush()
        self.publish_clock()

    def publish_clock(self):
        """SimNode publishes /clock here; nothing without ROS."""
