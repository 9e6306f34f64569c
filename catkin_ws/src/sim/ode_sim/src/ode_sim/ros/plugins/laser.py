"""Lidar plugins: libgazebo_ros_laser.so and libgazebo_ros_gpu_laser.so (gazebo_plugins
noetic-devel 2.9.2), both on the CPU ray caster (there is no GPU here; the rays hit the
collision shapes, as the non-GPU ray sensor does).

In a <sensor type="ray"> (or "gpu_ray"). Tags:
  topicName       default "/world" (sic, the original's default); relative names go under
                  robotNamespace
  frameName       default "/world"; header.frame_id is the name resolved as tf::resolve does
                  (see sensor_frame_name): the leading '/' is stripped, so the original
                  publishes "world", not "/world" (tf2 and RViz reject frame ids starting
                  with '/', and they never see one from this plugin either)
  robotNamespace  sensor plugins: missing = root namespace, present but empty = model name
  gaussianNoise, hokuyoMinIntensity, updateRate, alwaysOn: not read by the original laser
                  plugin (gaussianNoise belongs to gazebo_ros_block_laser); ignored here too:
                  noise comes from the sensor's <ray><noise> only.
Publishes sensor_msgs/LaserScan (queue 1) at the sensor's <update_rate> (0 = every physics
step) while someone subscribes: stamp = sim time of the measurement, angles and ranges as
ode_sim.engine.laser documents (Gazebo's ray sensor: rays start at range_min, nothing hit -> +inf,
below range_min -> -inf, noise then clamp). The rays start at the sensor frame
(link pose * sensor pose). Like Gazebo, the sensor sees every collision including its own
link's (a lidar inside its own collision box sees the box unless range_min reaches past it);
set EXCLUDE_OWN_LINK to drop the own link instead.
"""
import rospy
from sensor_msgs.msg import LaserScan

from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.rosio import SENSOR_QUEUE


#: Gazebo's ray sensor does not exclude the link carrying it; True drops that link's shapes.
EXCLUDE_OWN_LINK = False


def tf_resolve(prefix, frame):
    """tf::resolve (tf 1.13, noetic): '/x' -> 'x'; with a prefix 'p' (or '/p'): 'p/x'."""
    if frame.startswith('/'):
        return frame.lstrip('/')
    if prefix:
        return prefix.lstrip('/') + '/' + frame
    return frame


def sensor_frame_name(ns, frame):
    """The frame id gazebo_plugins publish: frameName resolved with the namespace (trailing
    slashes removed) as tf_prefix; the tf_prefix parameter is not consulted."""
    return tf_resolve(ns.rstrip('/'), frame)


def sensor_namespace(plugin):
    """GetRobotNamespace for sensor plugins: missing tag -> '' (root), empty -> model name."""
    if plugin.has('robotNamespace') and not plugin.params['robotNamespace'].strip():
        return plugin.model.name
    return plugin.ns


def sensor_world_pose(link, sensor):
    """The sensor frame in the world: the (lumped-frame aware) link frame * sensor pose."""
    return link.frame_pose(sensor.link) * sensor.pose


class LaserPlugin(Plugin):
    """libgazebo_ros_laser.so / libgazebo_ros_gpu_laser.so"""

    sensor_plugin = True
    sensor_types = ('ray', 'gpu_ray')

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if sensor is None or sensor.type not in self.sensor_types:
            raise self.error('must be inside a <sensor type="ray"> or <sensor type="gpu_ray">')
        import numpy as np
        from ode_sim.engine.laser import LaserModel
        self.ns = sensor_namespace(self)
        # seeded as the other sensors' noise (imu, gps, range, block_laser): a run's scans
        # are the same whatever the machine's load
        self.laser = LaserModel(sensor, rng=np.random.default_rng(0))
        if not self.has('frameName'):
            rospy.loginfo('%s: Laser plugin missing <frameName>, defaults to /world' % self.label)
        if not self.has('topicName'):
            rospy.loginfo('%s: Laser plugin missing <topicName>, defaults to /world' % self.label)
        self.frame_id = sensor_frame_name(self.ns, self.param('frameName', '/world',
                                                              warn=False).strip())
        topic = self.param('topicName', '/world', warn=False).strip()
        self.topic_name = self.topic(topic) if topic else ''
        self.pub = (self.ctx.io.publisher(self.topic_name, LaserScan, queue_size=SENSOR_QUEUE)
                    if topic else None)
        self.link_obj = self.link(sensor.link)
        self.exclude = {(model.name, self.link_obj.name)} if EXCLUDE_OWN_LINK else None
        self.set_rate(sensor.update_rate)
        self.scans = 0

    def sensor_pose(self):
        return sensor_world_pose(self.link_obj, self.sensor)

    def measure(self):
        """(ranges, intensities) of a scan taken now."""
        return self.laser.scan(self.ctx.raycaster(), self.sensor_pose(), self.exclude)

    def message(self):
        """A LaserScan taken now, stamped with the sim time."""
        from ode_sim.ros.convert import fill_laserscan
        ranges, intensities = self.measure()
        return fill_laserscan(None, self.laser, ranges, intensities, stamp=self.ctx.now(),
                              frame=self.frame_id)

    def next_update(self):
        return self._next_due_for(self.pub)

    def update(self):
        if self.pub is None or self.pub.get_num_connections() <= 0:
            return
        if not self.due():
            return
        self.pub.publish(self.message())
        self.scans += 1

    def shutdown(self):
        if self.pub is not None:
            try:
                self.pub.unregister()
            except Exception:  # noqa: BLE001 - shutting down anyway
                pass


PLUGINS = {
    'libgazebo_ros_laser.so': LaserPlugin,
    'libgazebo_ros_gpu_laser.so': LaserPlugin,
}
