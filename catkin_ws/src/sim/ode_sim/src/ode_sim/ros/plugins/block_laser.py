"""libgazebo_ros_block_laser.so (gazebo_plugins noetic-devel): sensor_msgs/PointCloud from a
ray sensor with vertical samples (a "block" of rays).

In a <sensor type="ray"> (or "gpu_ray"). Tags, defaults and INFO lines as the original:
`robotNamespace` (missing: root), `frameName` ("/world"), `topicName` ("/world"),
`gaussianNoise` (0), `hokuyoMinIntensity` (101, read and unused as in the original),
`updateRate` (0, read and unused: the sensor's <update_rate> paces it). header.frame_id is
tf::resolve(<ns>/tf_prefix, frameName).

Per published range (range_count x v_range_count, the sensor's <resolution>): the 4 surrounding
rays' raw ranges (the hit distance, range_max when nothing is hit), each at most
range_max - range_min, interpolated bilinearly; the direction is the middle of the rays used
(yaw = (ja + jb) / 2 steps, pitch likewise) and the point is (r cos p cos y, r cos p sin y,
-r sin p) in the sensor frame - z mirrored, as the original computes it. Points short of
range_max - range_min get the gaussianNoise on x, y and z; the one channel is the mean retro of
the 4 rays (plus noise). Published only while subscribed, stamped with the measurement's sim
time.
"""
import math
import random

import numpy as np
import rospy
from geometry_msgs.msg import Point32
from sensor_msgs.msg import ChannelFloat32, PointCloud

from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.laser import sensor_world_pose, tf_resolve
from ode_sim.ros.plugins.rosio import SENSOR_QUEUE, close, subscribed

EPSILON_DIFF = 1e-6     # the original's "at max range" comparison


def ray_hits(laser, caster, sensor_pose):
    """(raw ranges, retro) per ray, in the LaserModel's ray order (vertical outer); `caster`
    is the context's RayCaster."""
    dirs = sensor_pose.rotate(laser.directions)
    dist, who = caster.cast_hits(sensor_pose.p, dirs, laser.range_max, None,
                                 min_range=laser.range_min)
    d = np.asarray(dist, dtype=float)
    hit = np.isfinite(d) & (d < laser.range_max) & (np.asarray(who) >= 0)
    raw = np.where(hit, d, laser.range_max)
    retro = np.zeros(len(d))
    if hit.any():
        retro[hit] = caster.laser_retro()[np.asarray(who)[hit]]
    return raw, retro


def _corners(count_out, count_in, k):
    b = 0.0 if count_out == 1 else k * (count_in - 1) / (count_out - 1)
    a = int(math.floor(b))
    return a, min(a + 1, count_in - 1), b - math.floor(b)


def block_points(laser, raw, retro, noise=None):
    """[(x, y, z, intensity)] as the original's PutLaserData makes them; noise() draws one
    gaussian sample (None: no noise)."""
    n = noise or (lambda: 0.0)
    h_rays, v_rays = laser.samples, laser.v_samples
    cap = laser.range_max - laser.range_min
    r_all = np.minimum(np.asarray(raw).reshape(v_rays, h_rays), cap)
    t_all = np.asarray(retro).reshape(v_rays, h_rays)
    y_diff = laser.max_angle - laser.min_angle
    p_diff = laser.v_max_angle - laser.v_min_angle
    out = []
    for j in range(laser.v_range_count):
        va, vb, fv = _corners(laser.v_range_count, v_rays, j)
        for i in range(laser.range_count):
            ha, hb, fh = _corners(laser.range_count, h_rays, i)
            r1, r2 = r_all[va, ha], r_all[va, hb]
            r3, r4 = r_all[vb, ha], r_all[vb, hb]
            r = (1 - fv) * ((1 - fh) * r1 + fh * r2) + fv * ((1 - fh) * r3 + fh * r4)
            inten = 0.25 * (t_all[va, ha] + t_all[va, hb] + t_all[vb, ha] + t_all[vb, hb])
            yaw = (0.5 * (ha + hb) * y_diff / (h_rays - 1) if h_rays > 1 else 0.0) \
                + laser.min_angle
            pitch = (0.5 * (va + vb) * p_diff / (v_rays - 1) if v_rays > 1 else 0.0) \
                + laser.v_min_angle
            x = r * math.cos(pitch) * math.cos(yaw)
            y = r * math.cos(pitch) * math.sin(yaw)
            z = -r * math.sin(pitch)
            if abs(cap - r) >= EPSILON_DIFF:
                x, y, z = x + n(), y + n(), z + n()
            out.append((x, y, z, inten + n()))
    return out


class BlockLaser(Plugin):
    """libgazebo_ros_block_laser.so"""

    sensor_plugin = True

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if sensor is None or sensor.type not in ('ray', 'gpu_ray'):
            raise self.error('GazeboRosBlockLaser controller requires a Ray Sensor as its '
                             'parent')
        from ode_sim.engine.laser import LaserModel
        self.ns = self.params['robotNamespace'].strip() if self.has('robotNamespace') else ''
        self.laser = LaserModel(sensor)
        frame = self._info('frameName', '/world', 'defaults to /world')
        topic = self._info('topicName', '/world', 'defaults to /world')
        self.noise = float(self._info('gaussianNoise', 0.0, 'defaults to 0.0', float))
        self._info('hokuyoMinIntensity', 101.0, 'defaults to 101', float)
        self._info('updateRate', 0.0, 'defaults to 0', float)
        self.frame_id = tf_resolve(self._ns_tf_prefix(), frame)
        self.topic_name = self.topic(topic) if topic else ''
        self.pub = (ctx.io.publisher(self.topic_name, PointCloud, queue_size=SENSOR_QUEUE)
                    if topic else None)
        self.link_obj = self.link(sensor.link)
        self.rng = random.Random(0)
        self.set_rate(sensor.update_rate)

    def _info(self, tag, default, text, cast=str):
        if tag not in self.params:
            rospy.loginfo('Block laser plugin missing <%s>, %s' % (tag, text))
            return default
        return self.param(tag, default, cast) if cast is not str else self.params[tag].strip()

    def message(self):
        pose = sensor_world_pose(self.link_obj, self.sensor)
        raw, retro = ray_hits(self.laser, self.ctx.raycaster(), pose)
        noise = (lambda: self.rng.gauss(0.0, self.noise)) if self.noise > 0 else None
        msg = PointCloud()
        msg.header.stamp = self.ctx.now()
        msg.header.frame_id = self.frame_id
        ch = ChannelFloat32()
        for x, y, z, inten in block_points(self.laser, raw, retro, noise):
            msg.points.append(Point32(x, y, z))
            ch.values.append(inten)
        msg.channels = [ch]
        return msg

    def next_update(self):
        return self._next_due_for(self.pub)

    def update(self):
        if subscribed(self.pub) and self.due():
            self.pub.publish(self.message())

    def shutdown(self):
        close(self.pub)


PLUGINS = {'libgazebo_ros_block_laser.so': BlockLaser}
