"""What a plugin sees of the simulator, and the base class of the built-in plugins.

A URDF/SDF `<plugin filename="libgazebo_ros_X.so">` selects the class registered under that
file name (ode_sim.ros.plugins.REGISTRY). The node creates one instance per tag:

    plugin = cls(ctx, model, desc, sensor)

- ctx: PluginContext (below) — physics world, sim time, ray caster, renderer, TF.
- model: ode_sim.engine.physics.SimModel the plugin belongs to (links, joints, pose()).
- desc: ode_sim.description.model.Plugin (params dict of child tag -> text, the raw element).
- sensor: ode_sim.description.model.Sensor for sensor plugins (a plugin inside <sensor>), else None.

The node then calls, on the simulation thread:
- `before_step()` before every physics step, for plugins that override it (apply commands;
  the ros_control bridge blocks here in lockstep mode until the period's command arrived);
- `update()` after every physics step (the plugin checks `self.due()` for its own rate);
- `reset()` after /gazebo/reset_simulation or reset_world;
- `shutdown()` when its model is deleted or the node exits.
ROS callbacks run on rospy threads: keep state exchange simple (assign whole values).
"""
import math

import rospy

from ode_sim.description.model import ModelError
from ode_sim.ros.plugins.rosio import MemoryIO, WallClock, subscribed


NO_WORK = float('inf')       # next_update(): nothing to do until something changes


class PluginContext:
    """Filled by the node. Attributes:
    physics      ode_sim.engine.physics.PhysicsWorld
    world        ode_sim.description.model.World (lights, scene, physics settings)
    lockstep     bool: the ros_control bridge waits for each period's command
    tf           rosio.TfBatch (shared; the node sends one /tf message per step group)
    io           where plugins get publishers / subscribers / services (rosio.RosIO in the
                 node; default rosio.MemoryIO: no master needed)
    wall         the wall clock of wall-time waits (rosio.WallClock; tests: rosio.FakeClock)
    """

    def __init__(self, physics, world, lockstep=False, tf=None, io=None, wall=None):
        self.physics = physics
        self.world = world
        self.lockstep = lockstep
        self.tf = tf
        self.io = io if io is not None else MemoryIO()
        self.wall = wall if wall is not None else WallClock()
        self._raycaster = None
        self._ray_version = -1
        self._renderers = []
        self._render_version = -1

    def now(self):
        """Sim time as rospy.Time."""
        return rospy.Time.from_sec(self.physics.time)

    @property
    def time(self):
        return self.physics.time

    def raycaster(self):
        """A RayCaster over the current collision shapes of the world, on the physics'
        core: the compiled ray casting, or the NumPy reference with PhysicsWorld(core='python')."""
        from ode_sim.engine.raycast import RayCaster
        if self._raycaster is None:
            self._raycaster = RayCaster(self.physics.collision_shapes(), core=self.physics.core)
            self._ray_version = self.physics.version
        elif self._ray_version != self.physics.version:
            self._raycaster.set_shapes(self.physics.collision_shapes())
            self._ray_version = self.physics.version
        return self._raycaster

    def renderer(self, width, height, hfov, near=0.1, far=100.0, depth=False):
        """A new Renderer whose scene follows the world's visuals (see refresh_renderers)."""
        from ode_sim.engine.render import Renderer
        r = Renderer(width, height, hfov, near, far, depth=depth)
        self._set_scene(r)
        self._renderers.append(r)
        return r

    def refresh_renderers(self):
        """Called by users of renderers before rendering: rebuild scenes after model changes."""
        if self._render_version != self.physics.version:
            for r in self._renderers:
                self._set_scene(r)
            self._render_version = self.physics.version

    def _set_scene(self, r):
        w = self.world
        r.set_scene(self.physics.visual_shapes(), lights=w.lights, ambient=w.scene.ambient,
                    background=w.scene.background)


def _topic_join(ns, name):
    """GazeboRos-style: absolute names stay, relative ones go under the namespace."""
    if name.startswith('/'):
        return name
    ns = ns.strip('/')
    return '/' + (ns + '/' if ns else '') + name


class Plugin:
    """Base of the built-in plugins: parameter access with Gazebo's warnings, namespace, rate."""

    #: Gazebo's rule for the default robotNamespace: model plugins use the model name,
    #: sensor plugins the root namespace.
    sensor_plugin = False

    def __init__(self, ctx, model, desc, sensor=None):
        self.ctx = ctx
        self.model = model
        self.desc = desc
        self.sensor = sensor
        self.params = desc.params
        self.label = desc.filename.replace('lib', '', 1).replace('.so', '')
        if 'robotNamespace' in self.params:
            ns = self.params['robotNamespace'].strip()
        else:
            ns = '' if self.sensor_plugin else model.name
        if not ns and not self.sensor_plugin:
            ns = model.name
        self.ns = ns
        self._next = 0.0
        self.period = 0.0

    # -- parameters
    def has(self, tag):
        return tag in self.params

    def param(self, tag, default, cast=str, warn=True):
        """The value of <tag>, else `default` with Gazebo's WARN line."""
        if tag not in self.params:
            if warn:
                rospy.logwarn("%s(ns = %s): missing <%s>, defaults to %s"
                              % (self.label, self.ns or '/', tag, default))
            return default
        text = self.params[tag]
        try:
            if cast is bool:
                low = text.strip().lower()
                if low in ('1', 'true', 'yes'):
                    return True
                if low in ('0', 'false', 'no'):
                    return False
                raise ValueError(text)
            return cast(text.strip())
        except ValueError:
            raise ModelError("%s: plugin '%s' (%s) of model '%s': <%s> must be %s, got %r"
                             % (self.desc.source or self.model.desc.source, self.desc.name,
                                self.desc.filename, self.model.name, tag,
                                getattr(cast, '__name__', 'a value'), text))

    def error(self, what):
        """A ModelError naming this plugin."""
        return ModelError("%s: plugin '%s' (%s) of model '%s': %s"
                          % (self.desc.source or self.model.desc.source, self.desc.name,
                             self.desc.filename, self.model.name, what))

    def topic(self, name):
        return _topic_join(self.ns, name)

    def tf_frame(self, name):
        """A frame id as gazebo_plugins resolve it: tf::resolve(tf_prefix, name), tf_prefix
        searched upwards from the plugin's namespace (e.g. /robot2/tf_prefix, /tf_prefix)."""
        if name.startswith('/'):
            return name.lstrip('/')
        prefix = self._tf_prefix()
        return (prefix.strip('/') + '/' + name) if prefix.strip('/') else name

    def _tf_prefix(self):
        if not self.ctx.io.live:        # no ROS (MemoryIO): no parameter server
            return ''
        parts = [p for p in self.ns.split('/') if p]
        for i in range(len(parts), -1, -1):
            key = '/' + '/'.join(parts[:i] + ['tf_prefix'])
            try:
                if rospy.has_param(key):
                    return str(rospy.get_param(key))
            except Exception:           # master gone: no prefix
                return ''
        return ''

    def _ns_tf_prefix(self):
        """The `tf_prefix` parameter in the plugin's namespace only, not searched upwards
        (ros::NodeHandle(ns).getParam("tf_prefix") of the range, block_laser and bumper
        plugins)."""
        if not self.ctx.io.live:        # no ROS (MemoryIO): no parameter server
            return ''
        try:
            return str(rospy.get_param(self.topic('tf_prefix'), ''))
        except Exception:               # master gone: no prefix
            return ''

    def link(self, name):
        """The SimLink carrying `name` (a link, or a frame lumped into a link)."""
        if name in self.model.links:
            return self.model.links[name]
        for link in self.model.links.values():
            if name in link.desc.lumped:
                return link
        raise self.error("no link named '%s'" % name)

    def joint(self, name):
        j = self.model.joints.get(name)
        if j is None:
            raise self.error("couldn't get joint named '%s'" % name)
        return j

    # -- timing
    def set_rate(self, hz):
        self.period = 1.0 / hz if hz and hz > 0 else 0.0
        self._next = self.ctx.time

    def due(self):
        """True when the plugin's next update time has come (then schedules the next one)."""
        t = self.ctx.time
        if t + 1e-9 < self._next:
            return False
        if self.period > 0:
            self._next += self.period
            if self._next <= t:
                self._next = t + self.period
        return True

    def next_update(self):
        """When update() next has work: a sim time (the node may step up to it in one group,
        as fast as possible), NO_WORK, or None (update() or before_step() must run after every
        step: the default, for plugins that do not say otherwise)."""
        return None

    def _next_due(self):
        """next_update() of a plugin whose update() only acts when due()."""
        return self._next if self.period > 0 else None

    def _next_due_for(self, pub):
        """next_update() of a plugin whose update() only publishes on PUB when due(): NO_WORK
        while PUB has no subscriber."""
        return self._next_due() if subscribed(pub) else NO_WORK

    # -- lifecycle
    def before_step(self):
        pass

    def update(self):
        pass

    def reset(self):
        self._next = self.ctx.time

    def shutdown(self):
        pass


def rate_of(hz_text, default):
    try:
        v = float(hz_text)
    except (TypeError, ValueError):
        return default
    return v if v >= 0 and math.isfinite(v) else default
