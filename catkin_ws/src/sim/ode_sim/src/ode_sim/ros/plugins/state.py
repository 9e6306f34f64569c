"""Ground-truth state plugins: libgazebo_ros_p3d.so and libgazebo_ros_joint_state_publisher.so.

Parameter names, defaults and behaviour as gazebo_plugins (gazebo_ros_pkgs noetic-devel):

p3d (gazebo_ros_p3d.cpp): `bodyName` (required), `topicName` (required), `frameName` (world;
'world', '/world', 'map', '/map' mean the world, else a link of the model), `xyzOffset`,
`rpyOffset` (also accepted with a trailing s), `gaussianNoise` (0, on the twist; covariance
diagonals = noise^2), `updateRate` (0 = every step), `robotNamespace` (default: root).
Publishes nav_msgs/Odometry (pose of the body frame and its world twist; child_frame_id =
bodyName) only while someone subscribes.

joint_state_publisher (gazebo_ros_joint_state_publisher.cpp): `jointName` (comma separated),
`updateRate` (100 Hz), `robotNamespace` (default: the model name). Publishes
sensor_msgs/JointState on `joint_states` (position, velocity, and the applied effort).

This module also holds small helpers the other plugins share (parse_vector, gaussian);
message conversions are in ode_sim.ros.convert.
"""
import random

import numpy as np
import rospy

from ode_sim.ros.plugins.base import NO_WORK, Plugin
from ode_sim.ros.convert import fill_pose, fill_vector
from ode_sim.ros.plugins.rosio import SENSOR_QUEUE, close, subscribed
from ode_sim.description.transforms import Pose, quat_from_rpy


def parse_vector(plugin, tag, default=(0.0, 0.0, 0.0), warn=False):
    """<tag>x y z</tag> as a numpy 3-vector (bad text: ModelError naming the tag)."""
    text = plugin.param(tag, None, str, warn=warn)
    if text is None:
        return np.array(default, dtype=float)
    try:
        v = [float(s) for s in text.replace(',', ' ').split()]
    except ValueError:
        v = []
    if len(v) != 3:
        raise plugin.error("<%s> must be three numbers, got %r" % (tag, text))
    return np.array(v, dtype=float)


def gaussian(rng, sigma):
    return rng.gauss(0.0, sigma) if sigma > 0 else 0.0


WORLD_FRAMES = ('world', '/world', 'map', '/map')


# --------------------------------------------------------------------------- p3d
class P3D(Plugin):
    """libgazebo_ros_p3d.so: ground-truth odometry of one link."""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        # gazebo_ros_p3d: robotNamespace defaults to the root namespace
        self.ns = self.params['robotNamespace'].strip() if self.has('robotNamespace') else ''
        if not self.has('bodyName'):
            raise self.error("p3d plugin missing <bodyName>, cannot proceed")
        self.body_name = self.params['bodyName'].strip()
        self.body = self.link(self.body_name)
        if not self.has('topicName'):
            raise self.error("p3d plugin missing <topicName>, cannot proceed")
        self.topic_name = self.params['topicName'].strip()
        self.frame_name = self.param('frameName', 'world', warn=False)
        xyz_tag = 'xyzOffset' if self.has('xyzOffset') or not self.has('xyzOffsets') \
            else 'xyzOffsets'
        rpy_tag = 'rpyOffset' if self.has('rpyOffset') or not self.has('rpyOffsets') \
            else 'rpyOffsets'
        self.xyz_offset = parse_vector(self, xyz_tag)
        self.rpy_offset = parse_vector(self, rpy_tag)
        self.offset_q = np.array(quat_from_rpy(*self.rpy_offset))
        self.noise = self.param('gaussianNoise', 0.0, float, warn=False)
        self.set_rate(self.param('updateRate', 0.0, float, warn=False))
        self.rng = random.Random(0)
        self.reference = None
        self.active = True
        if self.frame_name not in WORLD_FRAMES:
            try:
                self.reference = self.link(self.frame_name)
            except Exception:
                rospy.logerr("gazebo_ros_p3d plugin: frameName: %s does not exist, will not "
                             "publish pose" % self.frame_name)
                self.active = False
        self.pub = None
        if self.active and self.topic_name:
            from nav_msgs.msg import Odometry
            self.pub = self.ctx.io.publisher(self.topic(self.topic_name), Odometry,
                                             queue_size=SENSOR_QUEUE)

    def _frame_state(self, link, name):
        pose = link.frame_pose(name)
        lin, ang = link.velocity(pose.p)
        return pose, lin, ang

    def measure(self):
        """nav_msgs/Odometry of the body now (noise applied)."""
        from nav_msgs.msg import Odometry
        pose, vpos, veul = self._frame_state(self.body, self.body_name)
        if self.reference is not None:
            fpose, fvpos, fveul = self._frame_state(self.reference, self.frame_name)
            pose = fpose.inverse() * pose
            vpos = fpose.inverse().rotate(vpos - fvpos)
            veul = fpose.inverse().rotate(veul - fveul)
        pos = pose.p + self.xyz_offset
        q = Pose((0, 0, 0), self.offset_q) * Pose((0, 0, 0), pose.q)
        msg = Odometry()
        msg.header.stamp = self.ctx.now()
        msg.header.frame_id = self.frame_name
        msg.child_frame_id = self.body_name
        fill_pose(msg.pose.pose, Pose(pos, q.q))
        n = self.noise
        fill_vector(msg.twist.twist.linear, [v + gaussian(self.rng, n) for v in vpos])
        fill_vector(msg.twist.twist.angular, [v + gaussian(self.rng, n) for v in veul])
        gn2 = n * n
        for i in (0, 7, 14, 21, 28, 35):
            msg.pose.covariance[i] = gn2
            msg.twist.covariance[i] = gn2
        return msg

    def next_update(self):
        return NO_WORK if not self.active or self.pub is None else self._next_due()

    def update(self):
        if not self.active or self.pub is None or not self.due():
            return
        if subscribed(self.pub):
            self.pub.publish(self.measure())

    def shutdown(self):
        close(self.pub)


# --------------------------------------------------------------------------- joint states
class JointStatePublisher(Plugin):
    """libgazebo_ros_joint_state_publisher.so: JointState of the listed joints."""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if not self.has('jointName'):
            rospy.logwarn("%s(ns = %s): missing <jointName>, publishing no joints"
                          % (self.label, self.ns))
            names = []
        else:
            names = [n for n in self.params['jointName'].replace(' ', '').split(',') if n]
        self.joints = [self.joint(n) for n in names]
        self.set_rate(self.param('updateRate', 100.0, float))
        from sensor_msgs.msg import JointState
        self.pub = self.ctx.io.publisher(self.topic('joint_states'), JointState, queue_size=1000)

    def measure(self):
        from sensor_msgs.msg import JointState
        msg = JointState()
        msg.header.stamp = self.ctx.now()
        msg.name = [j.name for j in self.joints]
        msg.position = [float(j.position()) for j in self.joints]
        msg.velocity = [float(j.velocity()) for j in self.joints]
        msg.effort = [float(j.effort()) for j in self.joints]
        return msg

    def next_update(self):
        return self._next_due()

    def update(self):
        if self.due() and subscribed(self.pub):
            self.pub.publish(self.measure())

    def shutdown(self):
        close(self.pub)


PLUGINS = {
    'libgazebo_ros_p3d.so': P3D,
    'libgazebo_ros_joint_state_publisher.so': JointStatePublisher,
}
