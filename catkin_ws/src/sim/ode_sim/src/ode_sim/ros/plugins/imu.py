"""IMU plugins: libgazebo_ros_imu.so (model plugin) and libgazebo_ros_imu_sensor.so (sensor
plugin inside <sensor type="imu">). Tags and defaults as gazebo_plugins (noetic-devel):

gazebo_ros_imu.cpp: bodyName (required), topicName (/default_imu), serviceName (/default_imu,
std_srvs/Empty, does nothing: "the IMU is always calibrated"), gaussianNoise (0), xyzOffset,
rpyOffset, updateRate (0 = every step), frameName (bodyName), robotNamespace (root).

gazebo_ros_imu_sensor.cpp: robotNamespace ('/<model>/'), topicName (imu_data, appended to the
namespace), frameName (required), updateRateHZ (1.0), gaussianNoise (0), xyzOffset (unused),
rpyOffset, initialOrientationAsReference (false: orientation relative to the world; true,
deprecated: relative to the sensor's orientation when loaded). The sensor's own <update_rate>
also limits the rate, and its <noise> (sensor.params) is added as Gazebo's ImuSensor does.

Both publish sensor_msgs/Imu only while someone subscribes: orientation of the frame in the
world (rpyOffset applied as offset * q), angular velocity and linear acceleration in the frame
of the body (model plugin) or of the sensor (sensor plugin). Linear acceleration is the proper
acceleration an accelerometer measures: (a - g) in that frame, +9.8 m/s^2 up at rest; a is the
body's acceleration from the physics (finite differences per step). (The original model plugin
reported a - without gravity - rotated the wrong way; we report what a real IMU reads.)
Noise: N(0, gaussianNoise) per component (the sensor plugin also on the quaternion components);
covariance diagonals gaussianNoise^2.
"""
import random

import numpy as np
import rospy

from ode_sim.ros.plugins.base import NO_WORK, Plugin
from ode_sim.ros.plugins.rosio import SENSOR_QUEUE, close, subscribed
from ode_sim.ros.convert import imu_msg
from ode_sim.ros.plugins.state import gaussian, parse_vector
from ode_sim.description.transforms import (Pose, qmul, qnormalize, qrotate_inv, quat_conjugate,
                                            quat_from_rpy)


class _Imu(Plugin):

    def _init_imu(self, link, local):
        """link: SimLink measured; local: Pose of the IMU frame in the link frame."""
        self.imu_link = link
        self.local = local
        self._local_q = local.tuples()[1]
        self.rng = random.Random(0)
        self.ctx.physics.track_acceleration(link)
        self.pub = None

    def gravity(self):
        return np.array(self.ctx.physics.gravity, dtype=float)

    def frame_state(self):
        """(world rotation quaternion of the IMU frame, angular velocity in that frame,
        proper linear acceleration in that frame), as float tuples."""
        link = self.imu_link
        _, q = link.pose_tuples(self._local_q)
        omega = link.angular_velocity()
        a = link.accel
        g = self.ctx.physics.gravity
        accel = (float(a[0]) - g[0], float(a[1]) - g[1], float(a[2]) - g[2])
        return q, qrotate_inv(q, omega), qrotate_inv(q, accel)

    def shutdown(self):
        close(self.pub, getattr(self, 'srv', None))


class GazeboRosImu(_Imu):
    """libgazebo_ros_imu.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        # gazebo_ros_imu: robotNamespace defaults to the root namespace
        self.ns = self.params['robotNamespace'].strip() if self.has('robotNamespace') else ''
        self.service_name = self.param('serviceName', '/default_imu', warn=False)
        self.topic_name = self.param('topicName', '/default_imu', warn=False)
        self.noise = self.param('gaussianNoise', 0.0, float, warn=False)
        if not self.has('bodyName'):
            raise self.error("imu plugin missing <bodyName>, cannot proceed")
        self.body_name = self.params['bodyName'].strip()
        link = self.link(self.body_name)
        self.xyz_offset = parse_vector(self, 'xyzOffset')
        self.rpy_offset = parse_vector(self, 'rpyOffset')
        self.offset_q = quat_from_rpy(*self.rpy_offset)
        self._offset_q = tuple(float(v) for v in self.offset_q)
        self.set_rate(self.param('updateRate', 0.0, float, warn=False))
        self.frame_name = self.param('frameName', self.body_name, warn=False)
        local = link.desc.lumped.get(self.body_name, Pose()) if self.body_name != link.name \
            else Pose()
        self._init_imu(link, local)
        self.srv = None
        if self.topic_name:
            from sensor_msgs.msg import Imu
            from std_srvs.srv import Empty, EmptyResponse
            self.pub = self.ctx.io.publisher(self.topic(self.topic_name), Imu, SENSOR_QUEUE)
            self.srv = self.ctx.io.service(self.topic(self.service_name), Empty,
                                           lambda req: EmptyResponse())

    def measure(self):
        q, omega, accel = self.frame_state()
        q = qnormalize(qmul(self._offset_q, q))
        n = self.noise
        stamp = self.ctx.now()
        omega = [v + gaussian(self.rng, n) for v in omega]
        accel = [v + gaussian(self.rng, n) for v in accel]
        return imu_msg(stamp, self.frame_name, q, omega, accel, n * n)

    def next_update(self):
        return NO_WORK if self.pub is None else self._next_due()

    def update(self):
        if self.pub is None or not self.due():
            return
        if subscribed(self.pub):
            self.pub.publish(self.measure())


class GazeboRosImuSensor(_Imu):
    """libgazebo_ros_imu_sensor.so"""

    sensor_plugin = True

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if sensor is None:
            raise self.error("libgazebo_ros_imu_sensor.so is a sensor plugin: put it inside "
                             "<sensor type=\"imu\">")
        if self.has('robotNamespace'):
            ns = self.params['robotNamespace'].strip() + '/'
        else:
            ns = '/' + model.name + '/'
            rospy.logwarn("missing <robotNamespace>, set to default: %s" % ns)
        self.ns = ns
        if self.has('topicName'):
            topic = ns + self.params['topicName'].strip()
        else:
            topic = ns + '/imu_data'
            rospy.logwarn("missing <topicName>, set to /namespace/default: %s" % topic)
        # the original advertises `topic` on a NodeHandle(ns): a relative ns ends up twice
        if not topic.startswith('/'):
            topic = '/' + ns + topic
        while '//' in topic:
            topic = topic.replace('//', '/')
        self.topic_name = topic.rstrip('/') or '/'
        if not self.has('frameName'):
            raise self.error("missing <frameName>, cannot proceed")
        self.frame_name = self.params['frameName'].strip()
        if self.has('updateRateHZ'):
            rate = self.param('updateRateHZ', 1.0, float)
        else:
            rate = 1.0
            rospy.logwarn("missing <updateRateHZ>, set to default: %s" % rate)
        if sensor.update_rate and sensor.update_rate > 0:
            rate = min(rate, sensor.update_rate) if rate > 0 else sensor.update_rate
        self.set_rate(rate)
        if self.has('gaussianNoise'):
            self.noise = self.param('gaussianNoise', 0.0, float)
        else:
            self.noise = 0.0
            rospy.logwarn("missing <gaussianNoise>, set to default: 0")
        self.xyz_offset = parse_vector(self, 'xyzOffset')
        self.rpy_offset = parse_vector(self, 'rpyOffset')
        self.offset_q = quat_from_rpy(*self.rpy_offset)
        self.initial_as_reference = self.param('initialOrientationAsReference', False, bool,
                                               warn=False)
        if self.initial_as_reference:
            rospy.logwarn("<initialOrientationAsReference> set to true, this behavior is "
                          "deprecated as of Gazebo 9 and will be removed in a future release")
        sp = sensor.params or {}
        self.gyro_noise = (float(sp.get('angular_velocity_noise_mean', sp.get('noise_mean', 0.0))),
                           float(sp.get('angular_velocity_noise_stddev',
                                        sp.get('noise_stddev', 0.0))))
        self.accel_noise = (float(sp.get('linear_acceleration_noise_mean',
                                         sp.get('noise_mean', 0.0))),
                            float(sp.get('linear_acceleration_noise_stddev',
                                         sp.get('noise_stddev', 0.0))))
        link = self.link(sensor.link)
        local = sensor.pose
        if sensor.link != link.name:
            local = link.desc.lumped.get(sensor.link, Pose()) * local
        self._init_imu(link, local)
        self.reference_q = np.array([0.0, 0.0, 0.0, 1.0])
        if self.initial_as_reference:
            self.reference_q = (link.pose() * local).q
        self._reference_conj = tuple(float(v) for v in quat_conjugate(self.reference_q))
        self._offset_q = tuple(float(v) for v in self.offset_q)
        from sensor_msgs.msg import Imu
        self.pub = self.ctx.io.publisher(self.topic_name, Imu, SENSOR_QUEUE)

    def measure(self):
        q, omega, accel = self.frame_state()
        q = qmul(self._offset_q, qmul(self._reference_conj, q))
        rng = self.rng
        mg, sg = self.gyro_noise
        ma, sa = self.accel_noise
        omega = [v + mg + gaussian(rng, sg) for v in omega]
        accel = [v + ma + gaussian(rng, sa) for v in accel]
        n = self.noise
        stamp = self.ctx.now()
        # the noise drawn in the original's order: orientation, acceleration, rate
        q = tuple(v + gaussian(rng, n) for v in q)
        accel = [v + gaussian(rng, n) for v in accel]
        omega = [v + gaussian(rng, n) for v in omega]
        return imu_msg(stamp, self.frame_name, q, omega, accel, n * n)

    def next_update(self):
        return self._next_due()

    def update(self):
        if not self.due():
            return
        if subscribed(self.pub):
            self.pub.publish(self.measure())


PLUGINS = {
    'libgazebo_ros_imu.so': GazeboRosImu,
    'libgazebo_ros_imu_sensor.so': GazeboRosImuSensor,
}
