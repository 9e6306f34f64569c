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
"""
import threading
import time
import xml.etree.ElementTree as ET

import numpy as np
import rospy
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs
from geometry_msgs.msg import Vector3
from std_msgs.msg import ColorRGBA
from std_srvs.srv import Empty, EmptyResponse
from visualization_msgs.msg import MarkerArray

from ode_sim.ros.convert import pose_from_msg, pose_msg, twist_msg, vector
from ode_sim.ros.markers import SceneMarkers
from ode_sim.ros.plugins.base import NO_WORK
from ode_sim.description.model import ModelError
from ode_sim.description.transforms import Pose, quat_to_matrix

WORLD_FRAMES = ('', 'world', 'map', '/map')

# gazebo_msgs/GetJointProperties type constants
JOINT_TYPES = {'revolute': 0, 'continuous': 1, 'prismatic': 2, 'fixed': 3, 'ball': 4,
               'universal': 5}
# ODE 0.16's joint parameter numbers (dParam*) that set_joint_properties reaches
ODE_PARAMS = (('hiStop', 1), ('loStop', 0), ('erp', 13), ('cfm', 8), ('stop_erp', 9),
              ('stop_cfm', 10), ('fudge_factor', 6), ('fmax', 5), ('vel', 2))
# SDF 1.6 <light><attenuation> defaults
ATTENUATION_DEFAULT = (1.0, 1.0, 0.0)


def _attenuation_of(light):
    vals = list(ATTENUATION_DEFAULT)
    att = light.find('attenuation')
    if att is not None:
        for i, tag in enumerate(('constant', 'linear', 'quadratic')):
            e = att.find(tag)
            if e is not None and e.text:
                try:
                    vals[i] = float(e.text)
                except ValueError:
                    pass
    return tuple(vals)


def light_attenuations(world_file):
    """{light name: (constant, linear, quadratic)} of the lights a world file declares or
    includes (model://sun); the description keeps only the range. {} when the file cannot be
    read."""
    import os
    from ode_sim.description.resolve import model_sdf_file, resolve_uri
    out = {}
    try:
        root = ET.parse(world_file).getroot()
    except (OSError, ET.ParseError, TypeError):
        return out
    world = root.find('world')
    if world is None:
        return out
    for light in world.findall('light'):
        if light.get('name'):
            out[light.get('name')] = _attenuation_of(light)
    for inc in world.findall('include'):
        uri = (inc.findtext('uri') or '').strip()
        try:
            path = resolve_uri(uri, os.path.dirname(os.path.abspath(world_file)))
            if os.path.isdir(path):
                path = model_sdf_file(path)
            light = ET.parse(path).getroot().find('light')
        except Exception:               # a model, or unreadable: no light here
            continue
        if light is None:
            continue
        name = (inc.findtext('name') or '').strip() or light.get('name')
        if name:
            out[name] = _attenuation_of(light)
    return out


def _seen_from(ref, pose, lin, ang):
    """(Pose msg, Twist msg) of a world-frame state as seen from a reference entity, `ref`
    being GazeboApi._frame's (pose, (lin, ang)) of it: what GetModelState and GetLinkState
    answer (velocities relative, expressed in the reference's axes)."""
    rpose, (rlin, rang) = ref
    inv = rpose.inverse()
    return pose_msg(inv * pose), twist_msg(inv.rotate(lin - rlin), inv.rotate(ang - rang))


class Job:
    """A wrench or joint effort of apply_body_wrench / apply_joint_effort, applied as
    gazebo_ros_api_plugin's schedulers do: before every step whose sim time t has
    start <= t <= start + duration (no end for a negative duration), removed once
    t > start + duration; start is at least the sim time of the request."""
    __slots__ = ('target', 'values', 'start', 'duration')

    def __init__(self, target, values, start, duration):
        self.target, self.values = target, values
        self.start, self.duration = start, duration

    def active(self, t):
        return t >= self.start and (self.duration < 0 or t <= self.start + self.duration)

    def expired(self, t):
        return self.duration >= 0 and t > self.start + self.duration


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


class GazeboApi:
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
        self.link_states = rospy.Publisher(n + '/link_states', gm.LinkStates, queue_size=10)
        self.model_states = rospy.Publisher(n + '/model_states', gm.ModelStates, queue_size=10)
        self.metrics = rospy.Publisher(n + '/performance_metrics', gm.PerformanceMetrics,
                                       queue_size=10)
        self._metrics_last = None       # (wall, sim) of the last metrics message
        rospy.Subscriber(n + '/set_link_state', gm.LinkState, self._set_link_state_topic)
        rospy.Subscriber(n + '/set_model_state', gm.ModelState, self._set_model_state_topic)
        self.markers = None
        self._scene = SceneMarkers(scene_frame)
        self._marker_version = -1
        self._next_marker = 0.0         # wall time of the next refresh
        node.step_hooks.append(self.after_step)
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

    def before_step(self):
        """The wrench and effort jobs, at the sim time the coming step starts from."""
        t = self.physics.time
        if self._wrenches:
            keep = []
            for job in self._wrenches:
                if job.active(t):
                    f, tau, point = job.values
                    job.target.add_force(f, point)
                    job.target.add_torque(tau)
                if not job.expired(t):
                    keep.append(job)
            self._wrenches = keep
        if self._efforts:
            keep = []
            for job in self._efforts:
                if job.active(t):
                    job.target.add_effort(job.values)
                if not job.expired(t):
                    keep.append(job)
            self._efforts = keep

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
        msg = gm.PerformanceMetrics()
        msg.header.stamp = rospy.Time.from_sec(t)
        msg.real_time_factor = (t - t0) / (wall - w0)
        self._metrics_last = (wall, t)
        self.metrics.publish(msg)

    def _model_states(self):
        msg = gm.ModelStates()
        for name, m in self.physics.models.items():
            msg.name.append(name)
            msg.pose.append(pose_msg(m.pose()))
            msg.twist.append(twist_msg(*m.twist()))
        return msg

    def _link_states(self):
        msg = gm.LinkStates()
        for mname, m in self.physics.models.items():
            for lname, link in m.links.items():
                msg.name.append('%s::%s' % (mname, lname))
                msg.pose.append(pose_msg(link.pose()))
                msg.twist.append(twist_msg(*link.velocity()))
        return msg

    def publish_markers(self):
        """(Under the node's lock.) Scene markers of every model not spawned from URDF (robots are shown by RViz's
        RobotModel): at once when models come or go, else twice a second of wall time while
        someone listens (furniture may be pushed around)."""
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
        name = req.model_name
        if name in self.physics.models:
            return gs.SpawnModelResponse(False, 'SpawnModel: Failure - entity already exists.')
        ref = self._frame(req.reference_frame)
        if ref is None:
            return gs.SpawnModelResponse(
                False, 'SpawnModel: Failure - reference frame [%s] not found'
                % req.reference_frame)
        source = 'spawn_%s_model(%s)' % (fmt, name)
        try:
            if fmt == 'urdf':
                desc = urdf.parse_urdf(req.model_xml, source, name)
            else:
                desc = sdf.parse_sdf_model(req.model_xml, source, name=name)
            desc.name = name
            desc.pose = ref[0] * pose_from_msg(req.initial_pose)
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
            m = self.physics.models.get(req.model_name)
            if m is None:
                rospy.logerr('DeleteModel: model [%s] does not exist' % req.model_name)
                return gs.DeleteModelResponse(False, 'DeleteModel: model does not exist')
            links = set(m.links.values())
            joints = set(m.joints.values())
            self._wrenches = [j for j in self._wrenches if j.target not in links]
            self._efforts = [j for j in self._efforts if j.target not in joints]
            self.node.remove_model(req.model_name)
        return gs.DeleteModelResponse(True, 'DeleteModel: successfully deleted model')

    # ----------------------------------------------------------------- model state
    def get_model_state(self, req):
        res = gs.GetModelStateResponse()
        m = self.physics.models.get(req.model_name)
        if m is None:
            rospy.logerr('GetModelState: model [%s] does not exist' % req.model_name)
            res.success = False
            res.status_message = 'GetModelState: model does not exist'
            return res
        seq = self._get_model_state_count.get(req.model_name, 0) + 1
        self._get_model_state_count[req.model_name] = seq
        res.header.seq = seq
        res.header.stamp = rospy.Time.from_sec(self.physics.time)
        res.header.frame_id = req.relative_entity_name
        with self.node.lock:
            ref = self._frame(req.relative_entity_name)
            if ref is None:
                res.success = False
                res.status_message = ('GetModelState: reference relative_entity_name not found, '
                                      'did you forget to scope the body by model name?')
                return res
            pose = m.pose()
            lin, ang = m.twist()
        res.pose, res.twist = _seen_from(ref, pose, lin, ang)
        res.success = True
        res.status_message = 'GetModelState: got properties'
        return res

    def _apply_model_state(self, state):
        m = self.physics.models.get(state.model_name)
        if m is None:
            rospy.logerr('Updating ModelState: model [%s] does not exist' % state.model_name)
            return False, 'SetModelState: model does not exist'
        ref = self._frame(state.reference_frame)
        if ref is None:
            rospy.logerr('Updating ModelState: for model[%s], specified reference frame entity '
                         '[%s] does not exist' % (state.model_name, state.reference_frame))
            return False, 'SetModelState: specified reference frame entity does not exist'
        rpose = ref[0]
        with self.node.lock:
            m.set_pose(rpose * pose_from_msg(state.pose))
            t = state.twist
            m.set_twist(rpose.rotate([t.linear.x, t.linear.y, t.linear.z]),
                        rpose.rotate([t.angular.x, t.angular.y, t.angular.z]))
        return True, 'SetModelState: set model state done'

    def set_model_state(self, req):
        ok, msg = self._apply_model_state(req.model_state)
        return gs.SetModelStateResponse(ok, msg)

    def _set_model_state_topic(self, msg):
        self._apply_model_state(msg)

    def set_model_configuration(self, req):
        m = self.physics.models.get(req.model_name)
        if m is None:
            rospy.logerr('SetModelConfiguration: model [%s] does not exist' % req.model_name)
            return gs.SetModelConfigurationResponse(
                False, 'SetModelConfiguration: model does not exist')
        if len(req.joint_names) != len(req.joint_positions):
            return gs.SetModelConfigurationResponse(
                False, 'SetModelConfiguration: joint name and position list have different '
                       'lengths')
        try:
            with self.node.lock:
                m.set_configuration(dict(zip(req.joint_names, req.joint_positions)))
        except ModelError as e:
            return gs.SetModelConfigurationResponse(False, 'SetModelConfiguration: %s' % e)
        return gs.SetModelConfigurationResponse(True, 'SetModelConfiguration: success')

    # ----------------------------------------------------------------- links
    def get_link_state(self, req):
        res = gs.GetLinkStateResponse()
        with self.node.lock:
            link = self._find_link(req.link_name)
            if link is None:
                res.success = False
                res.status_message = ('GetLinkState: link not found, did you forget to scope '
                                      'the link by model name?')
                return res
            ref = self._frame(req.reference_frame)
            if ref is None:
                res.success = False
                res.status_message = ('GetLinkState: reference reference_frame not found, did '
                                      'you forget to scope the link by model name?')
                return res
            pose = link.pose()
            lin, ang = link.velocity()
        res.link_state.link_name = req.link_name
        res.link_state.pose, res.link_state.twist = _seen_from(ref, pose, lin, ang)
        res.link_state.reference_frame = req.reference_frame
        res.success = True
        res.status_message = 'GetLinkState: got state'
        return res

    def _apply_link_state(self, state):
        link = self._find_link(state.link_name)
        if link is None or link.body is None:
            rospy.logerr('Updating LinkState: link [%s] does not exist' % state.link_name)
            return False, 'SetLinkState: link does not exist'
        ref = self._frame(state.reference_frame)
        if ref is None:
            rospy.logerr('Updating LinkState: reference_frame is not a valid entity name')
            return False, 'SetLinkState: failed'
        rpose = ref[0]
        with self.node.lock:
            t = state.twist
            link.set_state(rpose * pose_from_msg(state.pose), rpose.rotate(vector(t.linear)),
                           rpose.rotate(vector(t.angular)))
        return True, 'SetLinkState: success'

    def set_link_state(self, req):
        ok, msg = self._apply_link_state(req.link_state)
        return gs.SetLinkStateResponse(ok, msg)

    def _set_link_state_topic(self, msg):
        self._apply_link_state(msg)

    def get_link_properties(self, req):
        res = gs.GetLinkPropertiesResponse()
        link = self._find_link(req.link_name)
        if link is None:
            res.success = False
            res.status_message = ('GetLinkProperties: link not found, did you forget to scope '
                                  'the link by model name?')
            return res
        ine = link.desc.inertial
        res.gravity_mode = bool(link.desc.gravity)
        if ine is not None:
            res.com.position = Vector3(*[float(v) for v in ine.pose.p])
            res.mass = float(ine.mass)
            res.ixx, res.iyy, res.izz = float(ine.ixx), float(ine.iyy), float(ine.izz)
            res.ixy, res.ixz, res.iyz = float(ine.ixy), float(ine.ixz), float(ine.iyz)
        res.com.orientation.w = 1.0         # Gazebo: rotated inertia not reported
        res.success = True
        res.status_message = 'GetLinkProperties: got properties'
        return res

    def set_link_properties(self, req):
        link = self._find_link(req.link_name)
        if link is None:
            return gs.SetLinkPropertiesResponse(
                False, 'SetLinkProperties: link not found, did you forget to scope the link by '
                       'model name?')
        with self.node.lock:
            set_link_inertia(link, req)
        return gs.SetLinkPropertiesResponse(True, 'SetLinkProperties: properties set')

    def apply_body_wrench(self, req):
        with self.node.lock:
            link = self._find_link(req.body_name)
            if link is None:
                rospy.logerr('ApplyBodyWrench: body [%s] does not exist' % req.body_name)
                return gs.ApplyBodyWrenchResponse(False, 'ApplyBodyWrench: body does not exist')
            ref = self._frame(req.reference_frame)
            if ref is None:
                rospy.logerr('ApplyBodyWrench: reference_frame is not a valid entity name')
                return gs.ApplyBodyWrenchResponse(False,
                                                  'ApplyBodyWrench: reference_frame not found')
            # as Gazebo: the force acts at the centre of mass, the reference point adds
            # point x force to the torque (both in the reference frame's axes)
            rpose = ref[0]
            force = vector(req.wrench.force)
            torque = vector(req.wrench.torque) + np.cross(vector(req.reference_point), force)
            f = rpose.rotate(force)
            tau = rpose.rotate(torque)
            point = None
            start = max(req.start_time.to_sec(), self.physics.time)
            self._wrenches.append(Job(link, (f, tau, point), start, req.duration.to_sec()))
        return gs.ApplyBodyWrenchResponse(True, '')

    def _find_joint(self, name):
        for m in self.physics.models.values():
            if name in m.joints:
                return m.joints[name]
        return None

    def apply_joint_effort(self, req):
        with self.node.lock:
            joint = self._find_joint(req.joint_name)
            if joint is None:
                return gs.ApplyJointEffortResponse(False, 'ApplyJointEffort: joint not found')
            start = max(req.start_time.to_sec(), self.physics.time)
            self._efforts.append(Job(joint, float(req.effort), start, req.duration.to_sec()))
        return gs.ApplyJointEffortResponse(True, 'ApplyJointEffort: effort set')

    def clear_joint_forces(self, req):
        with self.node.lock:
            self._efforts = [e for e in self._efforts if e.target.name != req.joint_name]
        return gs.JointRequestResponse()

    def clear_body_wrenches(self, req):
        """body_name is the link's scoped name (model::link), as Gazebo compares it."""
        with self.node.lock:
            self._wrenches = [w for w in self._wrenches
                              if '%s::%s' % (w.target.model.name, w.target.name)
                              != req.body_name]
        return gs.BodyRequestResponse()

    # ----------------------------------------------------------------- joints
    def get_joint_properties(self, req):
        res = gs.GetJointPropertiesResponse()
        with self.node.lock:
            joint = self._find_joint(req.joint_name)
            if joint is None:
                res.success = False
                res.status_message = 'GetJointProperties: joint not found'
                return res
            res.type = JOINT_TYPES.get(joint.type, 0)
            res.position = [float(joint.position())]
            res.rate = [float(joint.velocity())]
        res.success = True
        res.status_message = 'GetJointProperties: got properties'
        return res

    def set_joint_properties(self, req):
        with self.node.lock:
            joint = self._find_joint(req.joint_name)
            if joint is None:
                return gs.SetJointPropertiesResponse(False,
                                                     'SetJointProperties: joint not found')
            c = req.ode_joint_config
            if c.damping:
                joint.desc.damping = float(c.damping[0])
                joint._update_active()
            if joint.hinge or joint.slider:
                for field, num in ODE_PARAMS:
                    values = getattr(c, field)
                    if values:
                        joint.joint.setParam(num, float(values[0]))
                if c.vel or c.fmax:
                    joint.child.wake()
        return gs.SetJointPropertiesResponse(True, 'SetJointProperties: properties set')

    # ----------------------------------------------------------------- lights
    def _light(self, name):
        for light in self.node.world.lights:
            if light.name == name:
                return light
        return None

    def _lights_changed(self):
        """Cameras re-read the world's lights at their next frame."""
        ctx = getattr(self.node, 'ctx', None)
        if ctx is not None:
            ctx._render_version = -1

    def get_light_properties(self, req):
        res = gs.GetLightPropertiesResponse()
        light = self._light(req.light_name)
        if light is None:
            res.success = False
            res.status_message = ('getLightProperties: Requested light %s not found!'
                                  % req.light_name)
            return res
        res.diffuse = ColorRGBA(*[float(v) for v in light.diffuse])
        (res.attenuation_constant, res.attenuation_linear,
         res.attenuation_quadratic) = self._attenuation.get(light.name, ATTENUATION_DEFAULT)
        res.success = True
        return res

    def set_light_properties(self, req):
        light = self._light(req.light_name)
        if light is None:
            return gs.SetLightPropertiesResponse(
                False, 'setLightProperties: Requested light %s not found!' % req.light_name)
        with self.node.lock:
            light.cast_shadows = bool(req.cast_shadows)
            d, sp = req.diffuse, req.specular
            light.diffuse = (d.r, d.g, d.b, d.a)
            light.specular = (sp.r, sp.g, sp.b, sp.a)
            light.direction = (req.direction.x, req.direction.y, req.direction.z)
            light.pose = pose_from_msg(req.pose)
            self._attenuation[light.name] = (req.attenuation_constant, req.attenuation_linear,
                                             req.attenuation_quadratic)
            self._lights_changed()
        return gs.SetLightPropertiesResponse(True, '')

    def delete_light(self, req):
        with self.node.lock:
            light = self._light(req.light_name)
            if light is None:
                return gs.DeleteLightResponse(
                    False, 'DeleteLight: Requested light %s not found!' % req.light_name)
            self.node.world.lights.remove(light)
            self._lights_changed()
        return gs.DeleteLightResponse(True, 'DeleteLight: %s successfully deleted'
                                      % req.light_name)

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
        m = self.physics.models.get(req.model_name)
        if m is None:
            rospy.logerr('GetModelProperties: model [%s] does not exist' % req.model_name)
            res.success = False
            res.status_message = 'GetModelProperties: model does not exist'
            return res
        res.parent_model_name = ''
        res.canonical_body_name = ''        # Gazebo leaves it empty
        res.body_names = list(m.links)
        res.geom_names = [c.name for l in m.desc.links for c in l.collisions]
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
        o = gm.ODEPhysics()
        o.auto_disable_bodies = self._auto_disable
        o.sor_pgs_precon_iters = int(self._precon_iters)
        o.sor_pgs_iters = int(p.iters)
        o.sor_pgs_w = float(p.sor)
        o.sor_pgs_rms_error_tol = 0.0       # Gazebo does not fill it either
        o.contact_surface_layer = float(p.contact_surface_layer)
        o.contact_max_correcting_vel = float(p.contact_max_correcting_vel)
        o.cfm = float(p.cfm)
        o.erp = float(p.erp)
        o.max_contacts = int(p.max_contacts)
        return (float(p.max_step_size), float(p.real_time_update_rate),
                tuple(float(v) for v in self.physics.gravity), bool(self.node.paused), o)

    def get_physics(self, _req):
        res = gs.GetPhysicsPropertiesResponse()
        with self.node.lock:
            res.time_step, res.max_update_rate, g, res.pause, res.ode_config = \
                self.physics_state()
        res.gravity = Vector3(*g)
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


def set_link_inertia(link, req):
    """set_link_properties on one link: mass, inertia (about the centre of mass, in the
    inertial frame's axes), centre of mass position and gravity mode; the link frame stays
    where it is."""
    from ode_sim.engine.bodies import ode_q
    ine = link.desc.inertial
    if ine is not None:
        ine.mass = float(req.mass)
        ine.ixx, ine.iyy, ine.izz = float(req.ixx), float(req.iyy), float(req.izz)
        ine.ixy, ine.ixz, ine.iyz = float(req.ixy), float(req.ixz), float(req.iyz)
        ine.pose = Pose((req.com.position.x, req.com.position.y, req.com.position.z),
                        ine.pose.q)
    link.desc.gravity = bool(req.gravity_mode)
    body = link.body
    if body is None or ine is None:
        return
    import ode
    frame = link.pose()
    lin, ang = link.velocity()
    r = quat_to_matrix(ine.pose.q)
    tensor = r @ ine.tensor() @ r.T
    mass = ode.Mass()
    mass.setParameters(max(ine.mass, 1e-9), 0, 0, 0, tensor[0, 0], tensor[1, 1], tensor[2, 2],
                       tensor[0, 1], tensor[0, 2], tensor[1, 2])
    body.setMass(mass)
    body.setGravityMode(bool(req.gravity_mode))
    com = Pose(ine.pose.p)
    link.com = com
    link._com_inv = com.inverse()
    link._ci_p, link._ci_q = link._com_inv.tuples()
    bp = frame * com
    body.setPosition(tuple(float(v) for v in bp.p))
    body.setQuaternion(ode_q(bp.q))
    body.setLinearVel(tuple(float(v) for v in lin + np.cross(ang, bp.p - frame.p)))
    link.wake()


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
