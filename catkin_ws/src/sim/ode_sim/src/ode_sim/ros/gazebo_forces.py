"""Forces and joints of gazebo_ros_api_plugin served by ode_sim (GazeboApi's ForceServices):
/gazebo/apply_body_wrench, apply_joint_effort, clear_joint_forces, clear_body_wrenches (the
jobs applied before every step of their sim-time window), get_joint_properties and
set_joint_properties; status texts as gazebo_ros_api_plugin's.
"""
import numpy as np
import rospy
from gazebo_msgs import srv as gs

from ode_sim.ros.convert import vector
from ode_sim.ros.gazebo_state import failure

# gazebo_msgs/GetJointProperties type constants
JOINT_TYPES = {'revolute': 0, 'continuous': 1, 'prismatic': 2, 'fixed': 3, 'ball': 4,
               'universal': 5}
# ODE 0.16's joint parameter numbers (dParam*) that set_joint_properties reaches
ODE_PARAMS = (('hiStop', 1), ('loStop', 0), ('erp', 13), ('cfm', 8), ('stop_erp', 9),
              ('stop_cfm', 10), ('fudge_factor', 6), ('fmax', 5), ('vel', 2))


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


class ForceServices:
    """GazeboApi's wrench, effort and joint services (mixin: uses self.node, self.physics,
    self._frame, self._find_link, self._wrenches, self._efforts)."""

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

    def apply_body_wrench(self, req):
        with self.node.lock:
            link = self._find_link(req.body_name)
            if link is None:
                rospy.logerr('ApplyBodyWrench: body [%s] does not exist' % req.body_name)
                return gs.ApplyBodyWrenchResponse(False, 'ApplyBodyWrench: body does not exist')
            ref, error = self._reference(req.reference_frame, 'ApplyBodyWrench: reference_frame not found',
                                         'ApplyBodyWrench: reference_frame is not a valid entity name')
            if error:
                return gs.ApplyBodyWrenchResponse(False, error)
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
                return failure(res, 'GetJointProperties: joint not found')
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
            joint.set_ode_properties(
                damping=c.damping[0] if c.damping else None,
                params=[(num, getattr(c, field)[0]) for field, num in ODE_PARAMS
                        if getattr(c, field)])
        return gs.SetJointPropertiesResponse(True, 'SetJointProperties: properties set')
