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


LINK_NOT_FOUND = '%s: link not found, did you forget to scope the link by model name?'
REFERENCE_NOT_FOUND = '%s: reference %s not found, did you forget to scope the %s by model name?'
SPAWN_REFERENCE_NOT_FOUND = 'SpawnModel: Failure - reference frame [%s] not found'


def failure(res, message):
    """RES (a response with success and status_message) answering that it failed: MESSAGE."""
    res.success = False
    res.status_message = message
    return res


class StateServices:
    """GazeboApi's state services (mixin: uses self.node, self.physics, self._frame,
    self._find_link, self._get_model_state_count). The lookups _model, _link and _reference
    serve every /gazebo/* service (gazebo_api.py, gazebo_forces.py, world_control.py too)."""

    # ----------------------------------------------------------------- lookups
    def _model(self, name, service, logged_as=None):
        """(the model NAME, None), or (None, "SERVICE: model does not exist") after logging
        gazebo_ros_api_plugin's "LOGGED_AS: model [NAME] does not exist" (LOGGED_AS: SERVICE
        unless given)."""
        m = self.physics.models.get(name)
        if m is not None:
            return m, None
        rospy.logerr('%s: model [%s] does not exist' % (logged_as or service, name))
        return None, '%s: model does not exist' % service

    def _link(self, name, service):
        """(the link NAME, 'model::link' or unique, None), or (None, "SERVICE: link not found,
        did you forget to scope the link by model name?")."""
        link = self._find_link(name)
        return (link, None) if link is not None else (None, LINK_NOT_FOUND % service)

    def _reference(self, name, message, logged=None):
        """(GazeboApi._frame of the reference entity NAME, None), or (None, MESSAGE) after
        logging LOGGED (when given) if NAME is no entity."""
        ref = self._frame(name)
        if ref is not None:
            return ref, None
        if logged:
            rospy.logerr(logged)
        return None, message

    def _seen_from(self, reference, state, message):
        """((Pose msg, Twist msg), None): the world-frame state STATE() = (pose, (lin, ang)) as
        seen from the reference entity REFERENCE, velocities relative and in its axes (what
        GetModelState and GetLinkState answer); or (None, MESSAGE) if REFERENCE is no entity."""
        with self.node.lock:
            ref, error = self._reference(reference, message)
            if error:
                return None, error
            pose, (lin, ang) = state()
        rpose, (rlin, rang) = ref
        inv = rpose.inverse()
        return (pose_msg(inv * pose), twist_msg(inv.rotate(lin - rlin), inv.rotate(ang - rang))), None

    # ----------------------------------------------------------------- models
    def get_model_state(self, req):
        res = gs.GetModelStateResponse()
        m, error = self._model(req.model_name, 'GetModelState')
        if error:
            return failure(res, error)
        seq = self._get_model_state_count.get(req.model_name, 0) + 1
        self._get_model_state_count[req.model_name] = seq
        res.header.seq = seq
        res.header.stamp = rospy.Time.from_sec(self.physics.time)
        res.header.frame_id = req.relative_entity_name
        seen, error = self._seen_from(req.relative_entity_name, lambda: (m.pose(), m.twist()),
                                      REFERENCE_NOT_FOUND % ('GetModelState', 'relative_entity_name', 'body'))
        if error:
            return failure(res, error)
        res.pose, res.twist = seen
        res.success = True
        res.status_message = 'GetModelState: got properties'
        return res

    def _apply_model_state(self, state):
        """/gazebo/set_model_state's topic and the service's work: (success, status text)."""
        m, error = self._model(state.model_name, 'SetModelState', logged_as='Updating ModelState')
        if error:
            return False, error
        ref, error = self._reference(
            state.reference_frame, 'SetModelState: specified reference frame entity does not exist',
            'Updating ModelState: for model[%s], specified reference frame entity [%s] does not '
            'exist' % (state.model_name, state.reference_frame))
        if error:
            return False, error
        rpose = ref[0]
        with self.node.lock:
            m.set_pose(rpose * pose_from_msg(state.pose))
            t = state.twist
            m.set_twist(rpose.rotate(xyz(t.linear)), rpose.rotate(xyz(t.angular)))
        return True, 'SetModelState: set model state done'

    def set_model_state(self, req):
        return gs.SetModelStateResponse(*self._apply_model_state(req.model_state))

    def set_model_configuration(self, req):
        m, error = self._model(req.model_name, 'SetModelConfiguration')
        if error:
            return gs.SetModelConfigurationResponse(False, error)
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
            link, error = self._link(req.link_name, 'GetLinkState')
            if not error:
                seen, error = self._seen_from(req.reference_frame, lambda: (link.pose(), link.velocity()),
                                              REFERENCE_NOT_FOUND % ('GetLinkState', 'reference_frame', 'link'))
        if error:
            return failure(res, error)
        res.link_state.link_name = req.link_name
        res.link_state.pose, res.link_state.twist = seen
        res.link_state.reference_frame = req.reference_frame
        res.success = True
        res.status_message = 'GetLinkState: got state'
        return res

    def _apply_link_state(self, state):
        """/gazebo/set_link_state's topic and the service's work: (success, status text)."""
        link = self._find_link(state.link_name)
        if link is None or link.body is None:
            rospy.logerr('Updating LinkState: link [%s] does not exist' % state.link_name)
            return False, 'SetLinkState: link does not exist'
        ref, error = self._reference(state.reference_frame, 'SetLinkState: failed',
                                     'Updating LinkState: reference_frame is not a valid entity name')
        if error:
            return False, error
        rpose = ref[0]
        with self.node.lock:
            t = state.twist
            link.set_state(rpose * pose_from_msg(state.pose), rpose.rotate(vector(t.linear)),
                           rpose.rotate(vector(t.angular)))
        return True, 'SetLinkState: success'

    def set_link_state(self, req):
        return gs.SetLinkStateResponse(*self._apply_link_state(req.link_state))

    def get_link_properties(self, req):
        res = gs.GetLinkPropertiesResponse()
        link, error = self._link(req.link_name, 'GetLinkProperties')
        if error:
            return failure(res, error)
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
        link, error = self._link(req.link_name, 'SetLinkProperties')
        if error:
            return gs.SetLinkPropertiesResponse(False, error)
        with self.node.lock:
            link.set_inertial(req.mass, (req.ixx, req.iyy, req.izz, req.ixy, req.ixz, req.iyz),
                              xyz(req.com.position), req.gravity_mode)
        return gs.SetLinkPropertiesResponse(True, 'SetLinkProperties: properties set')
