"""ROS wiring of ekf_localization_node: parameters, sensor subscribers, the output timer,
TF and the set_pose / enable / toggle interfaces."""
import threading

import numpy as np
import rospy
import tf2_ros
from nav_msgs.msg import Odometry
from geometry_msgs.msg import (PoseWithCovarianceStamped, TwistWithCovarianceStamped,
                               AccelWithCovarianceStamped)
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty, EmptyResponse

from . import conversions as conv
from . import sensors as S
from .ekf import Ekf, AX
from .filter_runner import FilterRunner
from .params import read as read_params, ParamError, unmeasured_errors
from robot_localization.srv import (SetPose, SetPoseResponse, ToggleFilterProcessing,
                                    ToggleFilterProcessingResponse)

LOG = {'debug': rospy.logdebug, 'info': rospy.loginfo, 'warn': rospy.logwarn,
       'error': rospy.logerr, 'fatal': rospy.logfatal}
FUTURE_TOLERANCE = 5.0   # s: a clock mix-up (wall vs sim time), not the lag of /clock under load


class EkfNode:
    def __init__(self):
        try:
            self.c = read_params(rospy.get_param, lambda lvl, text: LOG[lvl](text))
        except ParamError as e:
            rospy.logfatal(str(e))
            raise SystemExit(1)
        c = self.c
        self.lock = threading.Lock()
        ekf = Ekf(c.process_noise_covariance, c.initial_estimate_covariance)
        if c.initial_state is not None:
            ekf.reset(c.initial_state)
        self.runner = FilterRunner(ekf, c.sensor_timeout)
        self.runner.enabled = not c.disabled_at_startup
        for s in c.sensors:
            for w in S.config_warnings(s):
                rospy.logwarn(w)
        for w in unmeasured_errors(c.sensors, c.two_d_mode):
            rospy.logerr(w)
        self.tf_buffer = tf2_ros.Buffer()
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.tfb = tf2_ros.TransformBroadcaster() if c.publish_tf else None
        self.pub = rospy.Publisher('odometry/filtered', Odometry, queue_size=20)
        self.accel_pub = rospy.Publisher('accel/filtered', AccelWithCovarianceStamped,
                                         queue_size=20) if c.publish_acceleration else None
        self.subs = []
        for s in c.sensors:
            handler = {'odom': (Odometry, self.odom_callback), 'pose': (
                PoseWithCovarianceStamped, self.pose_callback), 'twist': (
                TwistWithCovarianceStamped, self.twist_callback), 'imu': (Imu, self.imu_callback)}
            msg_type, cb = handler[s.kind]
            self.subs.append(rospy.Subscriber(s.topic, msg_type, cb, callback_args=s,
                                              queue_size=s.queue_size))
            rospy.loginfo('Subscribed to %s (%s)', rospy.resolve_name(s.topic), s.name)
        self.set_pose_sub = rospy.Subscriber('set_pose', PoseWithCovarianceStamped, self.set_pose_callback)
        self.set_pose_srv = rospy.Service('set_pose', SetPose, self.set_pose_service)
        self.enable_srv = rospy.Service('~enable', Empty, self.enable_service)
        self.toggle_srv = rospy.Service('~toggle', ToggleFilterProcessing, self.toggle_service)
        self.last_published = None
        self.last_now = None
        self.timer = rospy.Timer(rospy.Duration(1.0 / c.frequency), self.periodic)

    # ---- warnings ---------------------------------------------------------------------------
    def _flush(self):
        for key, text in self.runner.warnings:
            if key == 'nan':
                rospy.logerr_throttle(1.0, text)
            else:
                rospy.logwarn_throttle(5.0, text)
        del self.runner.warnings[:]

    def _check_covariance(self, s, part, cov, flags, offset):
        for w in S.covariance_warnings(s.topic, part, cov, flags, offset):
            rospy.logwarn_throttle(10.0, w)
        d = np.diagonal(cov)
        return all(np.isfinite(d[i]) for i, f in enumerate(flags) if f)

    def _accept(self, s, header):
        stamp = header.stamp.to_sec()
        now = rospy.Time.now().to_sec()
        if stamp > now + FUTURE_TOLERANCE and now > 0:
            rospy.logwarn_throttle(5.0, 'The %s message is stamped %.2f s in the future; check the '
                                   'clock of its sender.' % (s.topic, stamp - now))
        with self.lock:
            ok = self.runner.accept_stamp(s.topic, stamp)
            self._flush()
        return ok, stamp

    def _lookup(self, target, source, stamp):
        """A transform target <- source or None (warns as the original)."""
        if not source or source == target:
            return None
        try:
            return self.tf_buffer.lookup_transform(target, source, stamp,
                                                   rospy.Duration(self.c.transform_timeout))
        except tf2_ros.ExtrapolationException:
            try:
                t = self.tf_buffer.lookup_transform(target, source, rospy.Time(0))
                rospy.logwarn_throttle(2.0, 'Transform from %s to %s was unavailable for the time '
                                       'requested. Using latest instead.' % (source, target))
                return t
            except tf2_ros.TransformException as e:
                err = e
        except tf2_ros.TransformException as e:
            err = e
        rospy.logwarn_throttle(2.0, 'Could not obtain transform from %s to %s. Error was %s'
                               % (source, target, err))
        return False

    # ---- sensor callbacks -------------------------------------------------------------------
    def _enqueue(self, *measurements):
        with self.lock:
            for m in measurements:
                self.runner.enqueue(m)

    def _pose_part(self, s, header, pose_msg, cov_list, time):
        flags = s.pose_flags
        if not any(flags):
            return None
        pose, norm = conv.pose_tuple(pose_msg)
        if any(flags[3:6]):
            if norm == 0.0:
                rospy.logwarn_throttle(5.0, 'The %s message contains an invalid orientation '
                                       'quaternion, but its configuration is such that orientation '
                                       'data is being used. Correcting...' % s.topic)
            elif abs(norm - 1.0) > 0.01:
                rospy.logwarn_once('An input was not normalized, this should NOT happen, but will '
                                   'normalize.')
        cov = conv.cov6(cov_list)
        if not self._check_covariance(s, 'pose', cov, flags, 0):
            return None
        t = self._lookup(self.c.world_frame, header.frame_id, header.stamp)
        if t is False:
            return None
        if t is not None:
            R = conv.rotation_matrix(t.transform.rotation)
            tr = t.transform.translation
            p = R @ np.array(pose[0:3]) + np.array([tr.x, tr.y, tr.z])
            rpy = conv.matrix_rpy(R @ S._rot(*pose[3:6]))
            pose = tuple(p) + tuple(rpy)
            R6 = np.zeros((6, 6))
            R6[0:3, 0:3] = R
            R6[3:6, 3:6] = R
            cov = R6 @ cov @ R6.T
        return S.pose_measurement(s, time, pose, cov, self.c.two_d_mode)

    def _twist_part(self, s, frame, twist_msg, cov_list, time, stamp):
        if not any(s.twist_flags):
            return None
        twist = conv.twist_tuple(twist_msg)
        cov = conv.cov6(cov_list)
        if not self._check_covariance(s, 'twist', cov, s.twist_flags, 6):
            return None
        t = self._lookup(self.c.base_link_frame, frame, stamp)
        if t is False:
            return None
        if t is not None:
            R = conv.rotation_matrix(t.transform.rotation)
            twist = tuple(R @ np.array(twist[0:3])) + tuple(R @ np.array(twist[3:6]))
            R6 = np.zeros((6, 6))
            R6[0:3, 0:3] = R
            R6[3:6, 3:6] = R
            cov = R6 @ cov @ R6.T
        return S.twist_measurement(s, time, twist, cov, self.c.two_d_mode)

    def odom_callback(self, msg, s):
        ok, time = self._accept(s, msg.header)
        if not ok:
            return
        pose_hdr = msg.header
        m1 = self._pose_part(s, pose_hdr, msg.pose.pose, msg.pose.covariance, time)
        child = msg.child_frame_id or self.c.base_link_frame
        m2 = self._twist_part(s, child, msg.twist.twist, msg.twist.covariance, time, msg.header.stamp)
        self._enqueue(m1, m2)

    def pose_callback(self, msg, s):
        ok, time = self._accept(s, msg.header)
        if ok:
            self._enqueue(self._pose_part(s, msg.header, msg.pose.pose, msg.pose.covariance, time))

    def twist_callback(self, msg, s):
        ok, time = self._accept(s, msg.header)
        if ok:
            self._enqueue(self._twist_part(s, msg.header.frame_id, msg.twist.twist,
                                           msg.twist.covariance, time, msg.header.stamp))

    def imu_callback(self, msg, s):
        ok, time = self._accept(s, msg.header)
        if not ok:
            return
        t = self._lookup(self.c.base_link_frame, msg.header.frame_id, msg.header.stamp)
        if t is False:
            return
        R = conv.rotation_matrix(t.transform.rotation) if t is not None else np.eye(3)
        two_d = self.c.two_d_mode
        out = []
        q = conv.quat_tuple(msg.orientation)
        norm = float(np.sqrt(sum(c * c for c in q)))
        orientation_used = any(s.config[3:6]) and msg.orientation_covariance[0] != -1
        R_world = None
        if norm == 0.0:
            if orientation_used:
                rospy.logwarn_throttle(5.0, 'The %s message contains an invalid orientation '
                                       'quaternion, but its configuration is such that orientation '
                                       'data is being used. Correcting...' % s.topic)
            q, norm = (1.0, 0.0, 0.0, 0.0), 1.0
        elif abs(norm - 1.0) > 0.01 and orientation_used:
            rospy.logwarn_once('An input was not normalized, this should NOT happen, but will normalize.')
        R_world = S._rot(*S.quaternion_to_rpy(q))
        if orientation_used:
            cov = conv.cov3(msg.orientation_covariance)
            if self._check_covariance(s, 'orientation', cov, s.config[3:6], 3):
                rpy = conv.matrix_rpy(R_world @ R.T)        # world<-imu * imu<-base
                out.append(S.imu_orientation_measurement(s, time, rpy, R @ cov @ R.T, two_d))
        if any(s.config[9:12]) and msg.angular_velocity_covariance[0] != -1:
            cov = conv.cov3(msg.angular_velocity_covariance)
            if self._check_covariance(s, 'angular_velocity', cov, s.config[9:12], 9):
                w = R @ np.array(conv.vector_tuple(msg.angular_velocity))
                out.append(S.imu_angular_measurement(s, time, w, R @ cov @ R.T, two_d))
        if any(s.config[12:15]) and msg.linear_acceleration_covariance[0] != -1:
            cov = conv.cov3(msg.linear_acceleration_covariance)
            if self._check_covariance(s, 'linear_acceleration', cov, s.config[12:15], 12):
                a = np.array(conv.vector_tuple(msg.linear_acceleration))
                if s.remove_gravitational_acceleration:
                    a = a - R_world.T @ np.array([0.0, 0.0, self.c.gravitational_acceleration])
                out.append(S.accel_measurement(s, time, R @ a, R @ cov @ R.T, two_d))
        self._enqueue(*out)

    # ---- services ---------------------------------------------------------------------------
    def _set_pose(self, msg):
        pose, _ = conv.pose_tuple(msg.pose.pose)
        with self.lock:
            self.runner.set_pose(msg.header.stamp.to_sec(), pose, conv.cov6(msg.pose.covariance))
        rospy.loginfo('Received set_pose request: x %.3f y %.3f z %.3f roll %.3f pitch %.3f yaw %.3f'
                      % pose)

    def set_pose_callback(self, msg):
        self._set_pose(msg)

    def set_pose_service(self, req):
        self._set_pose(req.pose)
        return SetPoseResponse()

    def enable_service(self, _req):
        if self.runner.enabled:
            rospy.logwarn('Asking for enabling filter service, but the filter was already enabled! '
                          'Use param disabled_at_startup.')
        else:
            rospy.loginfo('Enabling filter...')
            self.runner.enabled = True
        return EmptyResponse()

    def toggle_service(self, req):
        if req.on == self.runner.enabled:
            rospy.logwarn('Service was called to toggle filter processing but state was already as '
                          'requested.')
            return ToggleFilterProcessingResponse(status=False)
        rospy.loginfo('Toggling filter measurement filtering to %s.' % ('On' if req.on else 'Off'))
        self.runner.enabled = req.on
        return ToggleFilterProcessingResponse(status=True)

    # ---- output -----------------------------------------------------------------------------
    def periodic(self, _event):
        now = rospy.Time.now()
        nows = now.to_sec()
        if self.last_now is not None and nows < self.last_now and self.c.reset_on_time_jump:
            rospy.logwarn('Detected jump back in time. Resetting filter.')
            with self.lock:
                self.runner.ekf.reset()
                self.runner.last_stamp = {}
        self.last_now = nows
        with self.lock:
            if not self.runner.integrate(nows):
                self._flush()
                return
            ekf = self.runner.ekf
            if self.c.predict_to_current_time:
                ekf.predict(nows)
            x, P, t = ekf.x.copy(), ekf.P.copy(), ekf.last_time
            self._flush()
        stamp = rospy.Time.from_sec(t)
        if self.last_published is not None and stamp <= self.last_published:
            return
        self.last_published = stamp
        msg = conv.odometry(x, P, stamp, self.c.world_frame, self.c.base_link_frame_output)
        self.pub.publish(msg)
        if self.accel_pub is not None:
            a = AccelWithCovarianceStamped()
            a.header.stamp, a.header.frame_id = stamp, self.c.base_link_frame_output
            a.accel.accel.linear.x, a.accel.accel.linear.y, a.accel.accel.linear.z = \
                (float(v) for v in x[AX:AX + 3])
            cov = np.zeros((6, 6))
            cov[0:3, 0:3] = P[AX:AX + 3, AX:AX + 3]
            a.accel.covariance = [float(v) for v in cov.ravel()]
            self.accel_pub.publish(a)
        if self.tfb is not None and self.c.world_frame == self.c.odom_frame:
            offset = rospy.Duration.from_sec(self.c.transform_time_offset) \
                if self.c.transform_time_offset else None
            self.tfb.sendTransform(conv.transform(msg, self.c.invert_tf, offset))
        elif self.tfb is not None:
            self._publish_map_odom(msg)

    def _publish_map_odom(self, msg):
        try:
            t = self.tf_buffer.lookup_transform(self.c.odom_frame, self.c.base_link_frame, rospy.Time(0))
        except tf2_ros.TransformException:
            rospy.logerr_throttle(5.0, 'Could not obtain transform from %s->%s'
                                  % (self.c.odom_frame, self.c.base_link_frame))
            return
        from geometry_msgs.msg import TransformStamped
        Rm = conv.rotation_matrix(msg.pose.pose.orientation)
        pm = np.array([msg.pose.pose.position.x, msg.pose.pose.position.y, msg.pose.pose.position.z])
        Ro = conv.rotation_matrix(t.transform.rotation)
        tr = t.transform.translation
        po = np.array([tr.x, tr.y, tr.z])
        R = Rm @ Ro.T
        p = pm - R @ po
        out = TransformStamped()
        out.header.stamp = msg.header.stamp
        out.header.frame_id, out.child_frame_id = self.c.map_frame, self.c.odom_frame
        out.transform.translation.x, out.transform.translation.y, out.transform.translation.z = \
            (float(v) for v in p)
        q = S.rpy_to_quaternion(*conv.matrix_rpy(R))
        r = out.transform.rotation
        r.w, r.x, r.y, r.z = q
        self.tfb.sendTransform(out)


def main():
    rospy.init_node('ekf_navigation_node')
    EkfNode()
    rospy.spin()
