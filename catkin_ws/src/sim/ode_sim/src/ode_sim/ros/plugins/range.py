"""libgazebo_ros_range.so (gazebo_plugins noetic-devel): sensor_msgs/Range from a ray sensor,
the sonar / infrared range finder.

In a <sensor type="ray"> (or "gpu_ray"). Tags, defaults and log lines as the original:
  robotNamespace  missing: root namespace; given: that namespace
  topicName       "/range" (INFO when missing)
  frameName       "/world" (INFO when missing); header.frame_id = tf::resolve(<ns>/tf_prefix,
                  frameName)
  radiation       "ultrasound" (WARN when missing); anything else means INFRARED
  fov             0.05 rad (WARN when missing): field_of_view of the message
  gaussianNoise   0 (INFO when missing): added to the range when it is below max_range
  updateRate      0 (INFO when missing): a throttle on top of the sensor's <update_rate>
The rays are the sensor's (<horizontal>/<vertical> samples and angles, <range> min/max); the
range is the shortest raw ray (Gazebo's MultiRayShape ranges: a ray that hits nothing reads
range_max), then noise, then at most range_max. min_range / max_range are the sensor's.
Published only while subscribed, stamped with the sim time of the measurement.
"""
import random

import numpy as np
import rospy
from sensor_msgs.msg import Range

from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.laser import sensor_world_pose, tf_resolve
from ode_sim.ros.plugins.rosio import SENSOR_QUEUE, close, subscribed


def raw_ranges(laser, caster, sensor_pose):
    """Gazebo's raw ray ranges (MultiRayShape::GetRange) of a LaserModel: the hit distance,
    range_max when a ray hits nothing."""
    dirs = sensor_pose.rotate(laser.directions)
    dist, _who = caster.cast_hits(sensor_pose.p, dirs, laser.range_max, None,
                                  min_range=laser.range_min)
    d = np.asarray(dist, dtype=float)
    return np.where(np.isfinite(d) & (d < laser.range_max), d, laser.range_max)


class RangePlugin(Plugin):
    """libgazebo_ros_range.so"""

    sensor_plugin = True

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if sensor is None or sensor.type not in ('ray', 'gpu_ray'):
            raise self.error('GazeboRosRange controller requires a Ray Sensor as its parent')
        from ode_sim.engine.laser import LaserModel
        self.ns = self.params['robotNamespace'].strip() if self.has('robotNamespace') else ''
        self.laser = LaserModel(sensor)
        frame = self._tag('frameName', '/world', 'Range plugin missing <frameName>, '
                          'defaults to /world', rospy.loginfo)
        topic = self._tag('topicName', '/range', 'Range plugin missing <topicName>, '
                          'defaults to /range', rospy.loginfo)
        radiation = self._tag('radiation', 'ultrasound', 'Range plugin missing <radiation>, '
                              'defaults to ultrasound', rospy.logwarn)
        self.fov = self._number('fov', 0.05, 'Range plugin missing <fov>, defaults to 0.05',
                                rospy.logwarn)
        self.noise = self._number('gaussianNoise', 0.0, 'Range plugin missing '
                                  '<gaussianNoise>, defaults to 0.0', rospy.loginfo)
        rate = self._number('updateRate', 0.0, 'Range plugin missing <updateRate>, '
                            'defaults to 0', rospy.loginfo)
        self.throttle = 1.0 / rate if rate > 0 else 0.0
        self.last_publish = 0.0
        self.frame_id = tf_resolve(self._ns_tf_prefix(), frame)
        self.radiation = Range.ULTRASOUND if radiation == 'ultrasound' else Range.INFRARED
        self.topic_name = self.topic(topic) if topic else ''
        self.pub = (self.ctx.io.publisher(self.topic_name, Range, queue_size=SENSOR_QUEUE)
                    if topic else None)
        self.link_obj = self.link(sensor.link)
        self.rng = random.Random(0)
        self.set_rate(sensor.update_rate)

    def _tag(self, tag, default, line, log):
        if tag not in self.params:
            log(line)
            return default
        return self.params[tag].strip()

    def _number(self, tag, default, line, log):
        if tag not in self.params:
            log(line)
            return default
        return self.param(tag, default, float)

    def measure(self):
        """The range now: the shortest ray, noise added below max_range, at most max_range."""
        pose = sensor_world_pose(self.link_obj, self.sensor)
        r = float(np.min(raw_ranges(self.laser, self.ctx.raycaster(), pose)))
        if r < self.laser.range_max:
            noise = self.rng.gauss(0.0, self.noise) if self.noise > 0 else 0.0
            r = min(r + noise, self.laser.range_max)
        return r

    def message(self):
        msg = Range()
        msg.header.stamp = self.ctx.now()
        msg.header.frame_id = self.frame_id
        msg.radiation_type = self.radiation
        msg.field_of_view = self.fov
        msg.min_range = self.laser.range_min
        msg.max_range = self.laser.range_max
        msg.range = self.measure()
        return msg

    def next_update(self):
        return self._next_due_for(self.pub)

    def update(self):
        if not subscribed(self.pub) or not self.due():
            return
        t = self.ctx.time
        if t - self.last_publish < self.throttle - 1e-9:
            return
        self.last_publish = t
        self.pub.publish(self.message())

    def reset(self):
        super().reset()
        self.last_publish = 0.0

    def shutdown(self):
        close(self.pub)


PLUGINS = {'libgazebo_ros_range.so': RangePlugin}
