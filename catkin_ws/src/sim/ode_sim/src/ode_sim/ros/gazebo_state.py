"""Model and link state and properties of gazebo_ros_api_plugin served by ode_sim (GazeboApi's
StateServices): /gazebo/get_model_state, set_model_state (service and topic),
set_model_configuration, get_link_state, set_link_state (service and topic),
get_link_properties, set_link_properties; status texts as gazebo_ros_api_plugin's. States are
read and written relative to a reference entity (GazeboApi._frame).
"""
import rospy
from gazebo_msgs import srv as gs

from ode_sim.description.model import ModelError
from ode_sim.ros.convert import fill_vector, pose_from_msg, pose_msg, twist_msg, vector, xyz


def _seen_from(ref, pose, lin, ang):
    """(Pose msg, Twist msg) of a world-frame state as seen from a reference entity, `ref`
    being GazeboApi._frame's (pose, (lin, ang)) of it: what GetModelState and GetLinkState
    answer (velocities relative, expressed in the reference's axes)."""
    rpose, (rlin, rang) = ref
    inv = rpose.inverse()
    return pose_msg(inv * pose), twist_msg(inv.rotate(lin - rlin), inv.rotate(ang - rang))


class StateServices:
    """GazeboApi's state services (mixin: uses self.node, self.physics, self._frame,
    self._find_link, self._get_model_state_count)."""

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
            m.set_twist(rpose.rotate(xyz(t.linear)), rpose.rotate(xyz(t.angular)))
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
            fill_vector(res.com.position, ine.pose.p)
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
            link.set_inertial(req.mass, (req.ixx, req.iyy, req.izz, req.ixy, req.ixz, req.iyz),
                              xyz(req.com.position), req.gravity_mode)
        return gs.SetLinkPropertiesResponse(True, 'SetLinkProperties: properties set')
