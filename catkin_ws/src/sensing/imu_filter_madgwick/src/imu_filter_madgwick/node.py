"""ROS wiring of imu_filter_node: parameters, subscribers, publishers, TF."""
import copy

import rospy
import message_filters
import tf2_ros
from sensor_msgs.msg import Imu, MagneticField
from geometry_msgs.msg import Vector3Stamped, PoseStamped

from . import conversions
from .filter import WORLD_FRAMES, orientation_from_measurement, FreeFall
from .processor import Params, ImuProcessor, check_time_jump

THROTTLE = {'freefall': 5.0, 'zerostamp': 5.0, 'nonfinite': 5.0}


def read_params():
    p = Params()
    for name in ('gain', 'zeta', 'orientation_stddev', 'constant_dt', 'yaw_offset', 'declination',
                 'time_jump_threshold'):
        setattr(p, name, float(rospy.get_param('~' + name, getattr(p, name))))
    for name in ('use_mag', 'publish_tf', 'reverse_tf', 'publish_debug_topics', 'stateless',
                 'remove_gravity_vector'):
        setattr(p, name, bool(rospy.get_param('~' + name, getattr(p, name))))
    p.fixed_frame = str(rospy.get_param('~fixed_frame', p.fixed_frame))
    p.mag_bias = tuple(float(rospy.get_param('~mag_bias_' + a, 0.0)) for a in 'xyz')
    wf = str(rospy.get_param('~world_frame', 'enu'))
    if wf not in WORLD_FRAMES:
        rospy.logerr("The parameter world_frame was set to invalid value '%s'.", wf)
        rospy.logerr("Valid values are 'enu', 'ned' and 'nwu'. Setting to 'enu'.")
        wf = 'enu'
    p.world_frame = wf
    if p.constant_dt < 0.0:
        rospy.logfatal('constant_dt parameter is %f, must be >= 0.0. Setting to 0.0', p.constant_dt)
        p.constant_dt = 0.0
    if p.constant_dt == 0.0:
        rospy.loginfo('Using dt computed from message headers')
    else:
        rospy.loginfo('Using constant dt of %f sec', p.constant_dt)
    if p.remove_gravity_vector:
        rospy.loginfo('The gravity vector will be removed from the acceleration')
    else:
        rospy.loginfo('The gravity vector is kept in the IMU message.')
    return p


class ImuFilterRos:
    def __init__(self):
        self.p = read_params()
        self.proc = ImuProcessor(self.p)
        self.last_now = None
        self.received = False
        imu_ns = rospy.resolve_name('imu')
        self.pub = rospy.Publisher(imu_ns + '/data', Imu, queue_size=5)
        if self.p.publish_debug_topics:
            self.rpy_filtered = rospy.Publisher(imu_ns + '/rpy/filtered', Vector3Stamped, queue_size=5)
            self.rpy_raw = rospy.Publisher(imu_ns + '/rpy/raw', Vector3Stamped, queue_size=5) \
                if self.p.use_mag else None
            self.pose_pub = rospy.Publisher(imu_ns + '/orientation_filtered', PoseStamped, queue_size=5)
            self.tf_buffer = tf2_ros.Buffer()
            self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.tfb = tf2_ros.TransformBroadcaster() if self.p.publish_tf else None
        self.topics = [imu_ns + '/data_raw']
        if self.p.use_mag:
            self.topics.append(imu_ns + '/mag')
            imu_sub = message_filters.Subscriber(self.topics[0], Imu, queue_size=5)
            mag_sub = message_filters.Subscriber(self.topics[1], MagneticField, queue_size=5)
            self.sync = message_filters.ApproximateTimeSynchronizer([imu_sub, mag_sub], 5, 0.1)
            self.sync.registerCallback(self.imu_mag_callback)
        else:
            self.sub = rospy.Subscriber(self.topics[0], Imu, self.imu_callback, queue_size=5)
        self.wait_timer = rospy.Timer(rospy.Duration(10.0), self._check_waiting)

    def _check_waiting(self, _event):
        if not self.received:
            rospy.logwarn('Still waiting for data on topic(s) %s...', ' and '.join(self.topics))

    def _flush_warnings(self):
        for key, text in self.proc.warnings:
            if key == 'first':
                rospy.loginfo(text)
            else:
                rospy.logwarn_throttle(THROTTLE.get(key, 5.0), text)
        del self.proc.warnings[:]

    def _check_time_jump(self):
        now = rospy.Time.now().to_sec()
        if check_time_jump(self.last_now, now, self.p.time_jump_threshold):
            rospy.logwarn('Detected jump back in time of %.1f s. Resetting IMU filter.',
                          self.last_now - now)
            self.proc.reset()
        self.last_now = now

    def imu_callback(self, imu_msg):
        self._process(imu_msg, None)

    def imu_mag_callback(self, imu_msg, mag_msg):
        self._process(imu_msg, mag_msg)

    def _process(self, imu_msg, mag_msg):
        self.received = True
        self._check_time_jump()
        gyro, accel = conversions.imu_vectors(imu_msg)
        mag = conversions.mag_vector(mag_msg) if mag_msg is not None else None
        result = self.proc.process(imu_msg.header.stamp.to_sec(), gyro, accel, mag)
        self._flush_warnings()
        if result is None:
            return
        out = conversions.fill_imu(copy.deepcopy(imu_msg), result)
        self.pub.publish(out)
        if self.tfb is not None:
            self.tfb.sendTransform(conversions.transform(
                imu_msg.header, self.p.fixed_frame, result.filter_orientation, self.p.reverse_tf))
        if self.p.publish_debug_topics:
            self._publish_debug(imu_msg, result, accel, mag)

    def _publish_debug(self, imu_msg, result, accel, mag):
        self.rpy_filtered.publish(conversions.rpy_msg(imu_msg.header, result.orientation))
        if self.rpy_raw is not None and mag is not None:
            try:
                raw = orientation_from_measurement(accel, mag, self.p.world_frame)
                self.rpy_raw.publish(conversions.rpy_msg(imu_msg.header, raw))
            except FreeFall:
                pass
        translation = (0.0, 0.0, 0.0)
        try:
            t = self.tf_buffer.lookup_transform(self.p.fixed_frame, imu_msg.header.frame_id,
                                                imu_msg.header.stamp, rospy.Duration(0.1))
            tr = t.transform.translation
            translation = (tr.x, tr.y, tr.z)
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException):
            pass
        self.pose_pub.publish(conversions.pose_msg(imu_msg.header, self.p.fixed_frame,
                                                   result.orientation, translation))


def main():
    rospy.init_node('ImuFilter')
    ImuFilterRos()
    rospy.spin()
