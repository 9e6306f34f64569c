"""The /gazebo/* ROS API of gazebo_ros_api_plugin, served by ode_sim.

Services (gazebo_msgs / std_srvs): spawn_urdf_model, spawn_sdf_model, delete_model,
delete_light, get_model_properties, get_model_state, get_world_properties,
get_joint_properties, get_link_properties, get_link_state, get_light_properties,
set_light_properties, get_physics_properties, set_link_properties, set_physics_properties,
set_model_state, set_model_configuration, set_joint_properties, set_link_state, pause_physics,
unpause_physics, apply_body_wrench, apply_joint_effort, clear_joint_forces, clear_body_wrenches,
reset_simulation, reset_world; status texts as gazebo_ros_api_plugin's.
Topics: /gazebo/model_states, /gazebo/link_states (every step while subscribed),
/gazebo/performance_metrics (once a wall second while subscribed, as Gazebo >= 11.2),
/gazebo/set_model_state, /gazebo/set_link_state (subscribed). Physics dynamic_reconfigure:
physics_reconfigure.py. With enable_ros_network false none of these exist (only /clock).

/gazebo/scene_markers (ours, no Gazebo topic: the scene for RViz and the course web page in
place of gzclient) is advertised when the parameter ~scene_markers is true, or as soon as
something subscribes to it (SceneMarkerWatch polls the master once a wall second).

GazeboApi serves spawning, deleting, the world, physics and the per-step topics here; its
model/link state services are in gazebo_state.py, wrenches, efforts and joints in
gazebo_forces.py, lights in gazebo_lights.py (mixins over the same node and lock).
"""
import threading
import time

import numpy as np
import rospy
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs
from std_srvs.srv import Empty, EmptyResponse
from visualization_msgs.msg import MarkerArray

from ode_sim.description.model import ModelError
from ode_sim.description.transforms import Pose
from ode_sim.ros.convert import (EntityStatesFrame, fill_vector, ode_physics_msg,
                                 performance_metrics_msg, pose_from_msg, vector)
from ode_sim.ros.gazebo_forces import ForceServices
from ode_sim.ros.gazebo_lights import LightServices, light_attenuations
from ode_sim.ros.gazebo_state import SPAWN_REFERENCE_NOT_FOUND, StateServices, failure
from ode_sim.ros.markers import SceneMarkers
from ode_sim.ros.plugins.base import NO_WORK
from ode_sim.ros.plugins.rosio import FanoutPublisher

WORLD_FRAMES = ('', 'world', 'map', '/map')


def inject_namespace(desc, robot_namespace):
    """As gazebo_ros_api_plugin: every <plugin> lacking <robotNamespace> gets the spawn's
    robot_namespace (when one was given)."""
    if not robot_namespace:
        return
    plugins = list(desc.plugins)
    for link in desc.links:
        for sensor in link.sensors:
            plugins.extend(sensor.plugins)
    for p in plugins:
        if 'robotNamespace' not in p.params:
            p.params['robotNamespace'] = robot_namespace
    desc.robot_namespace = robot_namespace


class GazeboApi(StateServices, ForceServices, LightServices):
    """/gazebo/* of one SimNode: services, topics and the per-step hooks."""

    def __init__(self, node, scene_frame='odom', ns='/gazebo', scene_markers=False,
                 watch_markers=True):
        self.node = node
        self.ns = ns.rstrip('/')
        self.scene_frame = scene_frame
        n = self.ns
        S = rospy.Service
        self._wrenches = []             # Job(link, (force, torque, point))
        self._efforts = []              # Job(joint, effort)
        self._get_model_state_count = {}
        self._auto_disable = False      # ODE's world auto-disable flag as set_physics sets it
        self._precon_iters = 0
        self._attenuation = light_attenuations(node.world.source)
        self.services = [
            S(n + '/spawn_sdf_model', gs.SpawnModel, self.spawn_sdf),
            S(n + '/spawn_urdf_model', gs.SpawnModel, self.spawn_urdf),
            S(n + '/delete_model', gs.DeleteModel, self.delete_model),
            S(n + '/delete_light', gs.DeleteLight, self.delete_light),
            S(n + '/get_model_properties', gs.GetModelProperties, self.get_model_properties),
            S(n + '/get_model_state', gs.GetModelState, self.get_model_state),
            S(n + '/get_world_properties', gs.GetWorldProperties, self.get_world_properties),
            S(n + '/get_joint_properties', gs.GetJointProperties, self.get_joint_properties),
            S(n + '/get_link_properties', gs.GetLinkProperties, self.get_link_properties),
            S(n + '/get_link_state', gs.GetLinkState, self.get_link_state),
            S(n + '/get_light_properties', gs.GetLightProperties, self.get_light_properties),
            S(n + '/set_light_properties', gs.SetLightProperties, self.set_light_properties),
            S(n + '/get_physics_properties', gs.GetPhysicsProperties, self.get_physics),
            S(n + '/set_link_properties', gs.SetLinkProperties, self.set_link_properties),
            S(n + '/set_physics_properties', gs.SetPhysicsProperties, self.set_physics),
            S(n + '/set_model_state', gs.SetModelState, self.set_model_state),
            S(n + '/set_model_configuration', gs.SetModelConfiguration,
              self.set_model_configuration),
            S(n + '/set_joint_properties', gs.SetJointProperties, self.set_joint_properties),
            S(n + '/set_link_state', gs.SetLinkState, self.set_link_state),
            S(n + '/pause_physics', Empty, self.pause),
            S(n + '/unpause_physics', Empty, self.unpause),
            S(n + '/apply_body_wrench', gs.ApplyBodyWrench, self.apply_body_wrench),
            S(n + '/apply_joint_effort', gs.ApplyJointEffort, self.apply_joint_effort),
            S(n + '/clear_joint_forces', gs.JointRequest, self.clear_joint_forces),
            S(n + '/clear_body_wrenches', gs.BodyRequest, self.clear_body_wrenches),
            S(n + '/reset_simulation', Empty, self.reset_simulation),
            S(n + '/reset_world', Empty, self.reset_world),
        ]
        # every step while someone listens: sent by the compiled core's thread, as /clock
        self.link_states = FanoutPublisher(n + '/link_states', gm.LinkStates, queue_size=10)
        self.model_states = FanoutPublisher(n + '/model_states', gm.ModelStates, queue_size=10)
        self._link_frame = EntityStatesFrame(gm.LinkStates)
        self._model_frame = EntityStatesFrame(gm.ModelStates)
        self.metrics = rospy.Publisher(n + '/performance_metrics', gm.PerformanceMetrics,
                                       queue_size=10)
        self._metrics_last = None       # (wall, sim) of the last metrics message
        rospy.Subscriber(n + '/set_link_state', gm.LinkState, self._apply_link_state)
        rospy.Subscriber(n + '/set_model_state', gm.ModelState, self._apply_model_state)
        self.markers = None
        self._scene = SceneMarkers(scene_frame)
        self._marker_version = -1
        self._next_marker = 0.0         # wall time of the next refresh
        node.step_hooks.append(self.after_step)
        node.paused_hooks.append(self.while_paused)
        node.group_limits.append(self.next_update)
        node.before_step_hooks.append(self.before_step)
        self._watch = None
        if scene_markers:
            self.advertise_markers()
        elif watch_markers:
            self._watch = SceneMarkerWatch(self, n + '/scene_markers')

    def advertise_markers(self):
        """Advertise /gazebo/scene_markers (once) and publish the scene."""
        with self.node.lock:
            if self.markers is not None:
                return
            self.markers = rospy.Publisher(self.ns + '/scene_markers', MarkerArray,
                                           queue_size=1, latch=True)
            # under the node's lock as every entry into the engine: a spawn_model called at
            # the same time added a model while the scene was read ("dictionary changed size
            # during iteration": the simulator died at start-up)
            self.publish_markers()

    # ----------------------------------------------------------------- helpers
    @property
    def physics(self):
        return self.node.physics

    def _find_link(self, name):
        """'model::link' or a unique link name -> SimLink or None."""
        if '::' in name:
            mname, lname = name.split('::', 1)
            m = self.physics.models.get(mname)
            return m.links.get(lname) if m else None
        found = [m.links[name] for m in self.physics.models.values() if name in m.links]
        return found[0] if len(found) == 1 else None

    def _frame(self, name):
        """Pose and velocity source of a reference entity: (pose, (lin, ang)) or None."""
        if name in WORLD_FRAMES:
            return Pose(), (np.zeros(3), np.zeros(3))
        m = self.physics.models.get(name)
        if m is not None:
            return m.pose(), m.twist()
        link = self._find_link(name)
        if link is not None:
            return link.pose(), link.velocity()
        return None

    # ----------------------------------------------------------------- per step
    def next_update(self):
        """None (after every step) while wrenches or efforts are scheduled or model/link states
        are subscribed; else nothing to do per step (the node may step in groups)."""
        if self._wrenches or self._efforts or self.model_states.get_num_connections() > 0 \
                or self.link_states.get_num_connections() > 0:
            return None
        return NO_WORK

    def after_step(self):
        if self.model_states.get_num_connections() > 0:
            self.model_states.publish(self._model_states())
        if self.link_states.get_num_connections() > 0:
            self.link_states.publish(self._link_states())
        if self.markers is not None and (self.physics.version != self._marker_version or (
                time.monotonic() >= self._next_marker and self.markers.get_num_connections())):
            self.publish_markers()
        if self.metrics.get_num_connections() > 0:
            self.publish_metrics()
        else:
            self._metrics_last = None

    def while_paused(self):
        """Paused, nothing steps: a model spawned, deleted or moved from a window still
        reaches the scene markers at once (as gzserver keeps sending scene changes to its
        windows while paused)."""
        if self.markers is not None and self.physics.version != self._marker_version:
            self.publish_markers()

    def publish_metrics(self, wall=None):
        """gazebo_msgs/PerformanceMetrics once a wall second: the real-time factor over that
        second (sim seconds per wall second)."""
        wall = time.monotonic() if wall is None else wall
        t = self.physics.time
        if self._metrics_last is None:
            self._metrics_last = (wall, t)
            return
        w0, t0 = self._metrics_last
        if wall - w0 < 1.0:
            return
        if t < t0:                      # reset_simulation: start over
            self._metrics_last = (wall, t)
            return
        msg = performance_metrics_msg(t, (t - t0) / (wall - w0))
        self._metrics_last = (wall, t)
        self.metrics.publish(msg)

    def _model_states(self):
        names, states = [], []
        for name, m in self.physics.models.items():
            p, q = m.pose_tuples()
            names.append(name)
            states.append((p, q) + m.twist_tuples(p))
        return self._model_frame.message(tuple(names), states)

    def _link_states(self):
        names, states = [], []
        for mname, m in self.physics.models.items():
            for lname, link in m.links.items():
                p, q = link.pose_tuples()
                names.append('%s::%s' % (mname, lname))
                states.append((p, q) + link.point_velocity(p))
        return self._link_frame.message(tuple(names), states)

    def publish_markers(self):
        """(Under the node's lock.) Scene markers of every model not spawned from URDF (robots
        are shown by RViz's RobotModel): at once when models come or go, else twice a second
        of wall time while someone listens (furniture may be pushed around)."""
        self._marker_version = self.physics.version
        self._next_marker = time.monotonic() + 0.5
        robots = {n for n, m in self.physics.models.items() if m.desc.urdf}
        arr = self._scene.build(self.physics.visual_shapes(),
                                rospy.Time.from_sec(self.physics.time),
                                include=lambda s: s.model not in robots)
        self.markers.publish(arr)

    # ----------------------------------------------------------------- spawning
    def _spawn(self, req, fmt):
        from ode_sim.description import sdf, urdf
        from ode_sim.description.spawning import spawn_pose
        name = req.model_name
        if name in self.physics.models:
            return gs.SpawnModelResponse(False, 'SpawnModel: Failure - entity already exists.')
        ref, error = self._reference(req.reference_frame, SPAWN_REFERENCE_NOT_FOUND % req.reference_frame)
        if error:
            return gs.SpawnModelResponse(False, error)
        source = 'spawn_%s_model(%s)' % (fmt, name)
        try:
            if fmt == 'urdf':
                desc = urdf.parse_urdf(req.model_xml, source, name)
            else:
                desc = sdf.parse_sdf_model(req.model_xml, source, name=name)
            desc.name = name
            # initial_pose composed with the model's own pose, as gazebo_ros: spawning.py
            desc.pose = spawn_pose(pose_from_msg(req.initial_pose), desc.pose, ref[0])
            desc.source = desc.source or source
            inject_namespace(desc, req.robot_namespace)
            self.node.add_model(desc)
        except ModelError as e:
            rospy.logerr('ode_sim: %s' % e)
            return gs.SpawnModelResponse(False, 'SpawnModel: Failure - %s' % e)
        except Exception as e:      # never let a bad model kill the service thread silently
            rospy.logerr('ode_sim: spawning %s failed: %s: %s' % (name, type(e).__name__, e))
            self.node.remove_model(name)
            return gs.SpawnModelResponse(False, 'SpawnModel: Failure - %s: %s'
                                         % (type(e).__name__, e))
        return gs.SpawnModelResponse(True, 'SpawnModel: Successfully spawned entity')

    def spawn_urdf(self, req):
        return self._spawn(req, 'urdf')

    def spawn_sdf(self, req):
        from ode_sim.ros.world_control import spawn_light
        res = spawn_light(self, req)        # a <light>: world_control.py
        return res if res is not None else self._spawn(req, 'sdf')

    def delete_model(self, req):
        with self.node.lock:
            m, error = self._model(req.model_name, 'DeleteModel')
            if error:
                return gs.DeleteModelResponse(False, error)
            links = set(m.links.values())
            joints = set(m.joints.values())
            self._wrenches = [j for j in self._wrenches if j.target not in links]
            self._efforts = [j for j in self._efforts if j.target not in joints]
            self.node.remove_model(req.model_name)
        return gs.DeleteModelResponse(True, 'DeleteModel: successfully deleted model')

    # ----------------------------------------------------------------- world
    def get_world_properties(self, _req):
        res = gs.GetWorldPropertiesResponse()
        with self.node.lock:
            res.sim_time = self.physics.time
            res.model_names = list(self.physics.models)
        res.rendering_enabled = True        # Gazebo: "currently rendering is always enabled"
        res.success = True
        res.status_message = 'GetWorldProperties: got properties'
        return res

    def get_model_properties(self, req):
        res = gs.GetModelPropertiesResponse()
        m, error = self._model(req.model_name, 'GetModelProperties')
        if error:
            return failure(res, error)
        res.parent_model_name = ''
        res.canonical_body_name = ''        # Gazebo leaves it empty
        res.body_names = list(m.links)
        res.geom_names = [c.name for lk in m.desc.links for c in lk.collisions]
        res.joint_names = list(m.joints)
        res.child_model_names = []
        res.is_static = m.static
        res.success = True
        res.status_message = 'GetModelProperties: got properties'
        return res

    def physics_state(self):
        """The physics settings as get_physics_properties reports them:
        (time_step, max_update_rate, gravity, paused, ODEPhysics)."""
        p = self.node.world.physics
        o = ode_physics_msg(p, self._auto_disable, self._precon_iters)
        return (float(p.max_step_size), float(p.real_time_update_rate),
                tuple(float(v) for v in self.physics.gravity), bool(self.node.paused), o)

    def get_physics(self, _req):
        res = gs.GetPhysicsPropertiesResponse()
        with self.node.lock:
            res.time_step, res.max_update_rate, g, res.pause, res.ode_config = \
                self.physics_state()
        fill_vector(res.gravity, g)
        res.success = True
        res.status_message = 'GetPhysicsProperties: got properties'
        return res

    def set_physics(self, req):
        if not req.time_step > 0:
            return gs.SetPhysicsPropertiesResponse(
                False, 'SetPhysicsProperties: time_step must be positive, got %g'
                % req.time_step)
        p = self.node.world.physics
        o = req.ode_config
        with self.node.lock:
            p.max_step_size = req.time_step
            p.real_time_update_rate = max(0.0, req.max_update_rate)
            p.iters = max(1, int(o.sor_pgs_iters))
            p.sor = o.sor_pgs_w
            p.cfm, p.erp = o.cfm, o.erp
            p.contact_surface_layer = o.contact_surface_layer
            p.contact_max_correcting_vel = o.contact_max_correcting_vel
            p.max_contacts = max(1, int(o.max_contacts))
            self._auto_disable = bool(o.auto_disable_bodies)
            self._precon_iters = int(o.sor_pgs_precon_iters)
            self.physics.set_properties(
                time_step=req.time_step, gravity=vector(req.gravity), iters=p.iters,
                cfm=o.cfm, erp=o.erp, contact_surface_layer=o.contact_surface_layer,
                contact_max_correcting_vel=o.contact_max_correcting_vel,
                max_contacts=p.max_contacts)
            self.node._resync = True
        return gs.SetPhysicsPropertiesResponse(True, 'physics engine updated')

    def pause(self, _req):
        self.node.pause()
        return EmptyResponse()

    def unpause(self, _req):
        self.node.unpause()
        return EmptyResponse()

    def reset_simulation(self, _req):
        self.node.reset(time_too=True)
        return EmptyResponse()

    def reset_world(self, _req):
        self.node.reset(time_too=False)
        return EmptyResponse()


class SceneMarkerWatch(threading.Thread):
    """Advertises /gazebo/scene_markers once something subscribes to it (RViz with the scene
    display, the course web page's 3D view, rostopic echo): the master knows a subscriber
    before any publisher exists. Polls the master once a wall second until then."""

    def __init__(self, api, topic, period=1.0):
        super().__init__(name='scene_marker_watch', daemon=True)
        self.api, self.topic, self.period = api, topic, period
        self.start()

    def run(self):
        import rosgraph
        master = rosgraph.Master(rospy.get_name())
        while not rospy.is_shutdown() and self.api.markers is None:
            try:
                _pubs, subs, _srvs = master.getSystemState()
                if any(t == self.topic and nodes for t, nodes in subs):
                    self.api.advertise_markers()
                    return
            except Exception:           # master busy or gone: try again
                pass
            time.sleep(self.period)
