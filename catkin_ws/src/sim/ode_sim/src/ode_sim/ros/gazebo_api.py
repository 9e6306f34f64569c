"""The /gazebo/* ROS API of gazebo_ros_api_plugin, served by ode_sim.

Services (gazebo_msgs / std_srvs): spawn_urdf_model, spawn_sdf_model, delete_model,
get_model_state, set_model_state, set_model_configuration, get_world_properties,
get_model_properties, get_physics_properties, set_physics_properties, get_link_state,
set_link_state, apply_body_wrench, apply_joint_effort, clear_joint_forces, clear_body_wrenches,
pause_physics, unpause_physics, reset_simulation, reset_world.
Topics: /gazebo/model_states, /gazebo/link_states (every step while subscribed),
/gazebo/set_model_state, /gazebo/set_link_state (subscribed), /gazebo/scene_markers.
"""
import time

import numpy as np
import rospy
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs
from geometry_msgs.msg import Vector3
from std_srvs.srv import Empty, EmptyResponse
from visualization_msgs.msg import MarkerArray

from ode_sim.ros.convert import pose_from_msg, pose_msg, twist_msg, vector
from ode_sim.ros.markers import SceneMarkers
from ode_sim.ros.plugins.base import NO_WORK
from ode_sim.description.model import ModelError
from ode_sim.description.transforms import Pose

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


class GazeboApi:
    def __init__(self, node, scene_frame='odom', ns='/gazebo'):
        self.node = node
        self.ns = ns.rstrip('/')
        self.scene_frame = scene_frame
        n = self.ns
        S = rospy.Service
        self.services = [
            S(n + '/spawn_urdf_model', gs.SpawnModel, self.spawn_urdf),
            S(n + '/spawn_sdf_model', gs.SpawnModel, self.spawn_sdf),
            S(n + '/delete_model', gs.DeleteModel, self.delete_model),
            S(n + '/get_model_state', gs.GetModelState, self.get_model_state),
            S(n + '/set_model_state', gs.SetModelState, self.set_model_state),
            S(n + '/set_model_configuration', gs.SetModelConfiguration,
              self.set_model_configuration),
            S(n + '/get_world_properties', gs.GetWorldProperties, self.get_world_properties),
            S(n + '/get_model_properties', gs.GetModelProperties, self.get_model_properties),
            S(n + '/get_physics_properties', gs.GetPhysicsProperties, self.get_physics),
            S(n + '/set_physics_properties', gs.SetPhysicsProperties, self.set_physics),
            S(n + '/get_link_state', gs.GetLinkState, self.get_link_state),
            S(n + '/set_link_state', gs.SetLinkState, self.set_link_state),
            S(n + '/apply_body_wrench', gs.ApplyBodyWrench, self.apply_body_wrench),
            S(n + '/apply_joint_effort', gs.ApplyJointEffort, self.apply_joint_effort),
            S(n + '/clear_joint_forces', gs.JointRequest, self.clear_joint_forces),
            S(n + '/clear_body_wrenches', gs.BodyRequest, self.clear_body_wrenches),
            S(n + '/pause_physics', Empty, self.pause),
            S(n + '/unpause_physics', Empty, self.unpause),
            S(n + '/reset_simulation', Empty, self.reset_simulation),
            S(n + '/reset_world', Empty, self.reset_world),
        ]
        self.model_states = rospy.Publisher(n + '/model_states', gm.ModelStates, queue_size=1)
        self.link_states = rospy.Publisher(n + '/link_states', gm.LinkStates, queue_size=1)
        self.markers = rospy.Publisher(n + '/scene_markers', MarkerArray, queue_size=1,
                                       latch=True)
        rospy.Subscriber(n + '/set_model_state', gm.ModelState, self._set_model_state_topic)
        rospy.Subscriber(n + '/set_link_state', gm.LinkState, self._set_link_state_topic)
        self._wrenches = []             # (link, force, torque, point, end_time)
        self._efforts = []              # (joint, effort, end_time)
        self._scene = SceneMarkers(scene_frame)
        self._marker_version = -1
        self._next_marker = 0.0         # wall time of the next refresh
        node.step_hooks.append(self.after_step)
        node.group_limits.append(self.next_update)
        # under the node's lock as every entry into the engine: the spawn services above are
        # already up, and a spawn_model called at once added a model while the scene was read
        # ("dictionary changed size during iteration": the simulator died at start-up)
        with node.lock:
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
        """None (after every step) while wrenches or efforts last or model/link states are
        subscribed; else nothing to do per step (the node may step in groups)."""
        if self._wrenches or self._efforts or self.model_states.get_num_connections() > 0 \
                or self.link_states.get_num_connections() > 0:
            return None
        return NO_WORK

    def after_step(self):
        t = self.physics.time
        if self._wrenches:
            keep = []
            for link, f, tau, point, end in self._wrenches:
                if end is None or t <= end:
                    link.add_force(f, point)
                    link.add_torque(tau)
                    keep.append((link, f, tau, point, end))
            self._wrenches = keep
        if self._efforts:
            keep = []
            for joint, eff, end in self._efforts:
                if end is None or t <= end:
                    joint.add_effort(eff)
                    keep.append((joint, eff, end))
            self._efforts = keep
        if self.model_states.get_num_connections() > 0:
            self.model_states.publish(self._model_states())
        if self.link_states.get_num_connections() > 0:
            self.link_states.publish(self._link_states())
        if self.physics.version != self._marker_version or (
                time.monotonic() >= self._next_marker and self.markers.get_num_connections()):
            self.publish_markers()

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
        """Scene markers of every model not spawned from URDF (robots are shown by RViz's
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
        return self._spawn(req, 'sdf')

    def delete_model(self, req):
        if not self.node.remove_model(req.model_name):
            return gs.DeleteModelResponse(False, 'DeleteModel: model [%s] does not exist'
                                          % req.model_name)
        return gs.DeleteModelResponse(True, 'DeleteModel: successfully deleted model')

    # ----------------------------------------------------------------- model state
    def get_model_state(self, req):
        res = gs.GetModelStateResponse()
        res.header.stamp = rospy.Time.from_sec(self.physics.time)
        m = self.physics.models.get(req.model_name)
        if m is None:
            res.success = False
            res.status_message = 'GetModelState: model does not exist'
            return res
        ref = self._frame(req.relative_entity_name)
        if ref is None:
            res.success = False
            res.status_message = ('GetModelState: reference relative_entity_name not found, '
                                  'did you forget to scope the body by model name?')
            return res
        with self.node.lock:
            pose = m.pose()
            lin, ang = m.twist()
        rpose, (rlin, rang) = ref
        rel = rpose.inverse() * pose
        inv = rpose.inverse()
        res.header.frame_id = req.relative_entity_name
        res.pose = pose_msg(rel)
        res.twist = twist_msg(inv.rotate(lin - rlin), inv.rotate(ang - rang))
        res.success = True
        res.status_message = 'GetModelState: got properties'
        return res

    def _apply_model_state(self, state):
        m = self.physics.models.get(state.model_name)
        if m is None:
            return False, 'SetModelState: model [%s] does not exist' % state.model_name
        ref = self._frame(state.reference_frame)
        if ref is None:
            return False, ('SetModelState: specified reference frame entity [%s] does not exist'
                           % state.reference_frame)
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
        ok, text = self._apply_model_state(msg)
        if not ok:
            rospy.logwarn('ode_sim: %s' % text)

    def set_model_configuration(self, req):
        m = self.physics.models.get(req.model_name)
        if m is None:
            return gs.SetModelConfigurationResponse(
                False, 'SetModelConfiguration: model [%s] does not exist' % req.model_name)
        if len(req.joint_names) != len(req.joint_positions):
            return gs.SetModelConfigurationResponse(
                False, 'SetModelConfiguration: joint_names and joint_positions differ in length')
        try:
            with self.node.lock:
                m.set_configuration(dict(zip(req.joint_names, req.joint_positions)))
        except ModelError as e:
            return gs.SetModelConfigurationResponse(False, 'SetModelConfiguration: %s' % e)
        return gs.SetModelConfigurationResponse(True, 'SetModelConfiguration: success')

    # ----------------------------------------------------------------- links
    def get_link_state(self, req):
        res = gs.GetLinkStateResponse()
        link = self._find_link(req.link_name)
        if link is None:
            res.success = False
            res.status_message = 'GetLinkState: link not found'
            return res
        ref = self._frame(req.reference_frame)
        if ref is None:
            res.success = False
            res.status_message = 'GetLinkState: reference frame not found'
            return res
        rpose, (rlin, rang) = ref
        inv = rpose.inverse()
        lin, ang = link.velocity()
        res.link_state.link_name = req.link_name
        res.link_state.pose = pose_msg(inv * link.pose())
        res.link_state.twist = twist_msg(inv.rotate(lin - rlin), inv.rotate(ang - rang))
        res.link_state.reference_frame = req.reference_frame
        res.success = True
        res.status_message = 'GetLinkState: got state'
        return res

    def _apply_link_state(self, state):
        link = self._find_link(state.link_name)
        if link is None or link.body is None:
            return False, 'SetLinkState: link [%s] not found or static' % state.link_name
        ref = self._frame(state.reference_frame)
        if ref is None:
            return False, 'SetLinkState: reference frame [%s] not found' % state.reference_frame
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
        ok, text = self._apply_link_state(msg)
        if not ok:
            rospy.logwarn('ode_sim: %s' % text)

    def apply_body_wrench(self, req):
        link = self._find_link(req.body_name)
        if link is None:
            return gs.ApplyBodyWrenchResponse(False, 'ApplyBodyWrench: body not found')
        ref = self._frame(req.reference_frame)
        if ref is None:
            return gs.ApplyBodyWrenchResponse(False, 'ApplyBodyWrench: reference frame not found')
        rpose = ref[0]
        f = rpose.rotate([req.wrench.force.x, req.wrench.force.y, req.wrench.force.z])
        tau = rpose.rotate([req.wrench.torque.x, req.wrench.torque.y, req.wrench.torque.z])
        point = link.pose().apply([req.reference_point.x, req.reference_point.y,
                                   req.reference_point.z])
        start = req.start_time.to_sec()
        dur = req.duration.to_sec()
        end = None if dur < 0 else max(start, self.physics.time) + dur
        with self.node.lock:
            self._wrenches.append((link, f, tau, point, end))
        return gs.ApplyBodyWrenchResponse(True, '')

    def apply_joint_effort(self, req):
        joint = None
        for m in self.physics.models.values():
            if req.joint_name in m.joints:
                joint = m.joints[req.joint_name]
        if joint is None:
            return gs.ApplyJointEffortResponse(False, 'ApplyJointEffort: joint not found')
        dur = req.duration.to_sec()
        end = None if dur < 0 else max(req.start_time.to_sec(), self.physics.time) + dur
        with self.node.lock:
            self._efforts.append((joint, req.effort, end))
        return gs.ApplyJointEffortResponse(True, '')

    def clear_joint_forces(self, req):
        with self.node.lock:
            self._efforts = [e for e in self._efforts if e[0].name != req.joint_name]
        return gs.JointRequestResponse()

    def clear_body_wrenches(self, req):
        with self.node.lock:
            self._wrenches = [w for w in self._wrenches
                              if w[0].name != req.body_name
                              and '%s::%s' % (w[0].model.name, w[0].name) != req.body_name]
        return gs.BodyRequestResponse()

    # ----------------------------------------------------------------- world
    def get_world_properties(self, _req):
        res = gs.GetWorldPropertiesResponse()
        res.sim_time = self.physics.time
        res.model_names = list(self.physics.models)
        res.rendering_enabled = True
        res.success = True
        res.status_message = 'GetWorldProperties: got properties'
        return res

    def get_model_properties(self, req):
        res = gs.GetModelPropertiesResponse()
        m = self.physics.models.get(req.model_name)
        if m is None:
            res.success = False
            res.status_message = 'GetModelProperties: model does not exist'
            return res
        res.parent_model_name = ''
        res.canonical_body_name = m.canonical.name if m.canonical else ''
        res.body_names = list(m.links)
        res.geom_names = [c.name for l in m.desc.links for c in l.collisions]
        res.joint_names = list(m.joints)
        res.child_model_names = []
        res.is_static = m.static
        res.success = True
        res.status_message = 'GetModelProperties: got properties'
        return res

    def get_physics(self, _req):
        p = self.node.world.physics
        res = gs.GetPhysicsPropertiesResponse()
        res.time_step = p.max_step_size
        res.pause = self.node.paused
        res.max_update_rate = p.real_time_update_rate
        res.gravity = Vector3(*self.physics.gravity)
        o = res.ode_config
        o.auto_disable_bodies = False
        o.sor_pgs_precon_iters = 0
        o.sor_pgs_iters = int(p.iters)
        o.sor_pgs_w = p.sor
        o.sor_pgs_rms_error_tol = 0.0
        o.contact_surface_layer = p.contact_surface_layer
        o.contact_max_correcting_vel = p.contact_max_correcting_vel
        o.cfm = p.cfm
        o.erp = p.erp
        o.max_contacts = int(p.max_contacts)
        res.success = True
        res.status_message = 'GetPhysicsProperties: got properties'
        return res

    def set_physics(self, req):
        if req.time_step <= 0:
            return gs.SetPhysicsPropertiesResponse(False, 'SetPhysicsProperties: time_step must '
                                                   'be positive')
        p = self.node.world.physics
        o = req.ode_config
        with self.node.lock:
            p.max_step_size = req.time_step
            p.real_time_update_rate = max(0.0, req.max_update_rate)
            if o.sor_pgs_iters:
                p.iters = int(o.sor_pgs_iters)
            p.sor = o.sor_pgs_w or p.sor
            p.cfm, p.erp = o.cfm, o.erp
            p.contact_surface_layer = o.contact_surface_layer
            p.contact_max_correcting_vel = o.contact_max_correcting_vel
            if o.max_contacts:
                p.max_contacts = int(o.max_contacts)
            self.physics.set_properties(
                time_step=req.time_step, gravity=vector(req.gravity), iters=p.iters,
                cfm=o.cfm, erp=o.erp, contact_surface_layer=o.contact_surface_layer,
                contact_max_correcting_vel=o.contact_max_correcting_vel,
                max_contacts=p.max_contacts)
            self.node._resync = True
        return gs.SetPhysicsPropertiesResponse(True, 'SetPhysicsProperties: set')

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
