"""Model plugins that move things: libgazebo_ros_planar_move.so, libgazebo_ros_force.so,
libgazebo_ros_vacuum_gripper.so (gazebo_plugins noetic-devel). Each acts before every physics
step, as the originals act at WorldUpdateBegin.

planar_move (GazeboRosPlanarMove): `robotNamespace` (default root), `commandTopic` (cmd_vel),
`odometryTopic` (odom), `odometryFrame` (odom), `robotBaseFrame` (base_footprint),
`odometryRate` (20 Hz), `cmdTimeout` (-1: none; 0 keeps a command for its own step); each
missing tag but robotNamespace logs the original's WARN. Every step the model gets the
commanded velocity: (linear.x, linear.y) turned by the
model's yaw, z 0, and angular.z about z. Odometry (nav_msgs/Odometry, odom -> base frame, both
tf::resolve'd with the namespace's tf_prefix) and its TF go out when more than 1/odometryRate
s of sim time passed: the model's pose, the twist from the pose difference since the last
message (in the base frame), the original's fixed covariances.

force (GazeboRosForce): `robotNamespace` (default root), `bodyName` and `topicName`
(required: the original's FATAL line, the plugin does nothing). geometry_msgs/Wrench on
topicName; the last one received is applied in the world frame at the body's centre of mass
before every step until another arrives.

vacuum_gripper (GazeboRosVacuumGripper): `robotNamespace` (default root), `bodyName` and
`topicName` (required), `maxForce` (20 N), `maxDistance` (0.05 m), `minDistance` (0.01 m).
Services `<ns>/on`, `<ns>/off` (std_srvs/Empty); topicName: std_msgs/Bool, whether it grasps,
every step while subscribed. While on, every link of another model whose origin lies within
maxDistance of the gripper link's origin takes the gripper link's velocities, is pulled by a
force of min(1/d, maxForce) along the offset (in the held link's axes, as the original
computes it) and, within minDistance, is moved onto the gripper's position.

joint_pose_trajectory (GazeboRosJointPoseTrajectory): `robotNamespace` (default root),
`topicName` (set_joint_trajectory), `serviceName` (read; the original builds its service only
with ENABLE_SERVICE, so neither offers it), `updateRate` (INFO when missing; unused, as in the
original). trajectory_msgs/JointTrajectory on topicName; header.frame_id "world", "map" or
"/map" keeps the model's pose, a link name ("model::link" or unique) keeps that link where it
is. From max(header.stamp, now) on, each step applies the next point's positions (joints set
kinematically, velocities zeroed) and moves the start on by that point's time_from_start (the
original's accumulation), until the points are used up.
"""
import math

import numpy as np
import rospy
from geometry_msgs.msg import TransformStamped, Twist, Wrench
from nav_msgs.msg import Odometry
from std_msgs.msg import Bool
from std_srvs.srv import Empty, EmptyResponse

from ode_sim.ros.convert import fill_pose
from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.laser import tf_resolve
from ode_sim.ros.plugins.rosio import close, subscribed
from ode_sim.description.transforms import Pose, yaw_of


def _root_ns(plugin):
    return plugin.params['robotNamespace'].strip() if plugin.has('robotNamespace') else ''


class PlanarMove(Plugin):
    """libgazebo_ros_planar_move.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        self.ns = _root_ns(self)
        self.label = 'PlanarMovePlugin'
        self.command_topic = self._warned('commandTopic', 'cmd_vel', '"cmd_vel"')
        self.odometry_topic = self._warned('odometryTopic', 'odom', '"odom"')
        self.odometry_frame = self._warned('odometryFrame', 'odom', '"odom"')
        self.base_frame = self._warned('robotBaseFrame', 'base_footprint', '"base_footprint"')
        if self.has('odometryRate'):
            self.odometry_rate = self.param('odometryRate', 20.0, float)
        else:
            rospy.logwarn('PlanarMovePlugin (ns = %s) missing <odometryRate>, defaults to %f'
                          % (self.ns, 20.0))
            self.odometry_rate = 20.0
        if self.has('cmdTimeout'):
            self.cmd_timeout = self.param('cmdTimeout', -1.0, float)
        else:
            rospy.logwarn('PlanarMovePlugin (ns = %s) missing <cmdTimeout>, defaults to %f'
                          % (self.ns, -1.0))
            self.cmd_timeout = -1.0
        prefix = self._tf_prefix()     # tf::getPrefixParam, searched upwards
        self.odom_frame_id = tf_resolve(prefix, self.odometry_frame)
        self.base_frame_id = tf_resolve(prefix, self.base_frame)
        self.cmd = (0.0, 0.0, 0.0)
        self.last_cmd_time = ctx.time
        self.last_odom_time = ctx.time
        self.last_pose = model.pose()
        self.sub = ctx.io.subscriber(self.topic(self.command_topic),
                                     Twist,
                                     self.on_cmd_vel, queue_size=1)
        self.odom_pub = ctx.io.publisher(self.topic(self.odometry_topic), Odometry,
                                         queue_size=1)
        if ctx.tf is not None:
            ctx.tf.sendTransform([])    # advertises /tf, as the original's broadcaster does
        self.odometries = 0

    def _warned(self, tag, default, shown):
        if not self.has(tag):
            rospy.logwarn('PlanarMovePlugin (ns = %s) missing <%s>, defaults to %s'
                          % (self.ns, tag, shown))
            return default
        return self.params[tag].strip()

    def on_cmd_vel(self, msg):
        self.cmd = (msg.linear.x, msg.linear.y, msg.angular.z)
        self.last_cmd_time = self.ctx.time

    def before_step(self):
        t = self.ctx.time
        if self.cmd_timeout >= 0 and t - self.last_cmd_time > self.cmd_timeout:
            self.cmd = (0.0, 0.0, 0.0)
        x, y, rot = self.cmd
        yaw = yaw_of(self.model.pose().q)
        c, s = math.cos(yaw), math.sin(yaw)
        self.model.set_twist((x * c - y * s, y * c + x * s, 0.0), (0.0, 0.0, rot))

    def update(self):
        if self.odometry_rate <= 0:
            return
        t = self.ctx.time
        dt = t - self.last_odom_time
        if dt > 1.0 / self.odometry_rate + 1e-9:     # Gazebo's exact sec/nsec time
            self.publish_odometry(dt)
            self.last_odom_time = t

    def publish_odometry(self, dt):
        pose = self.model.pose()
        stamp = self.ctx.now()
        odom = Odometry()
        odom.header.stamp = stamp
        odom.header.frame_id = self.odom_frame_id
        odom.child_frame_id = self.base_frame_id
        fill_pose(odom.pose.pose, pose)
        odom.pose.pose.position.z = 0.0          # the original fills x and y only
        cov = [0.0] * 36
        cov[0], cov[7], cov[14], cov[21], cov[28], cov[35] = (1e-5, 1e-5, 1e12, 1e12, 1e12,
                                                              1e-3)
        odom.pose.covariance = cov
        vx = (pose.p[0] - self.last_pose.p[0]) / dt
        vy = (pose.p[1] - self.last_pose.p[1]) / dt
        rot = self.cmd[2]
        if rot > math.pi / dt:
            odom.twist.twist.angular.z = rot
        else:
            last, cur = yaw_of(self.last_pose.q), yaw_of(pose.q)
            while cur < last - math.pi:
                cur += 2 * math.pi
            while cur > last + math.pi:
                cur -= 2 * math.pi
            odom.twist.twist.angular.z = (cur - last) / dt
        self.last_pose = pose
        yaw = yaw_of(pose.q)
        odom.twist.twist.linear.x = math.cos(yaw) * vx + math.sin(yaw) * vy
        odom.twist.twist.linear.y = math.cos(yaw) * vy - math.sin(yaw) * vx
        if self.ctx.tf is not None:
            tr = TransformStamped()
            tr.header.stamp = stamp
            tr.header.frame_id = self.odom_frame_id
            tr.child_frame_id = self.base_frame_id
            tr.transform.translation.x, tr.transform.translation.y, \
                tr.transform.translation.z = (float(v) for v in pose.p)
            q = tr.transform.rotation
            q.x, q.y, q.z, q.w = (float(v) for v in pose.q)
            self.ctx.tf.sendTransform([tr])
        self.odom_pub.publish(odom)
        self.odometries += 1

    def reset(self):
        super().reset()
        self.cmd = (0.0, 0.0, 0.0)
        self.last_odom_time = self.ctx.time
        self.last_pose = self.model.pose()

    def shutdown(self):
        close(self.sub, self.odom_pub)


class Force(Plugin):
    """libgazebo_ros_force.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        self.ns = _root_ns(self)
        self.body = None
        self.sub = None
        self.wrench = (np.zeros(3), np.zeros(3))
        if not self.has('bodyName'):
            rospy.logfatal('force plugin missing <bodyName>, cannot proceed')
            return
        name = self.params['bodyName'].strip()
        if name not in model.links:
            rospy.logfatal('gazebo_ros_force plugin error: bodyName: %s does not exist' % name)
            return
        if not self.has('topicName'):
            rospy.logfatal('force plugin missing <topicName>, cannot proceed')
            return
        self.body = model.links[name]
        self.sub = ctx.io.subscriber(self.topic(self.params['topicName'].strip()), Wrench,
                                     self.on_wrench, queue_size=1)

    def on_wrench(self, msg):
        self.wrench = (np.array([msg.force.x, msg.force.y, msg.force.z]),
                       np.array([msg.torque.x, msg.torque.y, msg.torque.z]))

    def before_step(self):
        if self.body is None:
            return
        f, tau = self.wrench
        if f.any() or tau.any():
            self.body.add_force(f)
            self.body.add_torque(tau)

    def shutdown(self):
        close(self.sub)


class VacuumGripper(Plugin):
    """libgazebo_ros_vacuum_gripper.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        self.ns = _root_ns(self)
        self.on = False
        self.link_obj = None
        self.pub = None
        self.services = []
        self.grasping = False
        if not self.has('bodyName'):
            rospy.logfatal('vacuum_gripper plugin missing <bodyName>, cannot proceed')
            return
        name = self.params['bodyName'].strip()
        if name not in model.links:
            rospy.logfatal('gazebo_ros_vacuum_gripper plugin error: link named: %s does not '
                           'exist' % name)
            rospy.logfatal('gazebo_ros_vacuum_gripper plugin error: You should check it '
                           'exists and is not connected with fixed joint')
            rospy.logfatal('gazebo_ros_vacuum_gripper plugin error: Found links are: %s'
                           % ''.join(' ' + n for n in model.links))
            return
        if not self.has('topicName'):
            rospy.logfatal('vacuum_gripper plugin missing <serviceName>, cannot proceed')
            return
        self.link_obj = model.links[name]
        self.max_force = self.param('maxForce', 20.0, float, warn=False)
        self.max_distance = self.param('maxDistance', 0.05, float, warn=False)
        self.min_distance = self.param('minDistance', 0.01, float, warn=False)
        self.pub = ctx.io.publisher(self.topic(self.params['topicName'].strip()), Bool,
                                    queue_size=1)
        self.services = [ctx.io.service(self.topic('on'), Empty, self.on_service),
                         ctx.io.service(self.topic('off'), Empty, self.off_service)]
        rospy.loginfo('Loaded gazebo_ros_vacuum_gripper')

    def on_service(self, _req):
        if self.on:
            rospy.logwarn("gazebo_ros_vacuum_gripper: already status is 'on'")
        else:
            self.on = True
            rospy.loginfo('gazebo_ros_vacuum_gripper: status: off -> on')
        return EmptyResponse()

    def off_service(self, _req):
        if self.on:
            self.on = False
            rospy.loginfo('gazebo_ros_vacuum_gripper: status: on -> off')
        else:
            rospy.logwarn("gazebo_ros_vacuum_gripper: already status is 'off'")
        return EmptyResponse()

    def before_step(self):
        if self.link_obj is None:
            return
        grasping = False
        if self.on:
            grasping = self.hold()
        self.grasping = grasping
        if subscribed(self.pub):
            self.pub.publish(Bool(data=grasping))

    def hold(self):
        """One step of the vacuum: True when some link is within reach."""
        gripper = self.link_obj
        gp = gripper.pose()
        lin, ang = gripper.velocity()
        held = False
        for m in list(self.ctx.physics.models.values()):
            if m is self.model or m.name == gripper.name:
                continue
            for link in m.links.values():
                if link.body is None:
                    continue
                lp = link.pose()
                diff = lp.inverse().rotate(gp.p - lp.p)     # parent_pose - link_pose
                norm = float(np.linalg.norm(diff))
                if norm > self.max_distance:
                    continue
                body = link.body
                body.setLinearVel(tuple(float(v) for v in lin))
                body.setAngularVel(tuple(float(v) for v in ang))
                if norm <= self.min_distance:
                    link.set_state(Pose(gp.p, lp.q), lin, ang)
                force = min(1.0 / norm, self.max_force) if norm > 0 else self.max_force
                if norm > 0:
                    link.add_force(force * diff / norm)
                link.wake()
                held = True
        return held

    def shutdown(self):
        close(self.pub, *self.services)


class JointPoseTrajectory(Plugin):
    """libgazebo_ros_joint_pose_trajectory.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        from trajectory_msgs.msg import JointTrajectory
        self.ns = _root_ns(self)
        topic = self.param('topicName', 'set_joint_trajectory', warn=False).strip()
        self.service_name = self.param('serviceName', 'set_joint_trajectory', warn=False)
        if not self.has('updateRate'):
            rospy.loginfo('joint trajectory plugin missing <updateRate>, defaults to 0.0 (as '
                          'fast as possible)')
        self.target = model
        self.reference = None
        self.joints = []
        self.points = []
        self.index = 0
        self.start = 0.0
        self.active = False
        self.sub = (ctx.io.subscriber(self.topic(topic), JointTrajectory, self.on_trajectory,
                                      queue_size=100) if topic else None)

    def _find_link(self, name):
        physics = self.ctx.physics
        if '::' in name:
            mname, lname = name.split('::', 1)
            m = physics.models.get(mname)
            return m.links.get(lname) if m else None
        found = [m.links[name] for m in physics.models.values() if name in m.links]
        return found[0] if found else None

    def on_trajectory(self, msg):
        ref = msg.header.frame_id
        reference = None
        target = self.model
        if ref not in ('world', '/map', 'map'):
            reference = self._find_link(ref)
            if reference is None:
                rospy.logerr('ros_joint_trajectory plugin needs a reference link [%s] as '
                             'frame_id, aborting.' % ref)
                return
            target = reference.model
        points = [(p.time_from_start.to_sec(), list(p.positions)) for p in msg.points]
        start = max(msg.header.stamp.to_sec(), self.ctx.time)
        # one assignment each: the simulation thread reads them together
        self.target, self.reference = target, reference
        self.joints, self.points, self.index, self.start = list(msg.joint_names), points, 0, \
            start
        self.active = True

    def before_step(self):
        if not self.active:
            return
        t = self.ctx.time
        if t + 1e-9 < self.start:
            return
        if self.index >= len(self.points):
            self.active = False
            self.reference = None
            return
        tfs, positions = self.points[self.index]
        rospy.loginfo('time [%f] updating configuration [%d/%d]'
                      % (t, self.index, len(self.points)))
        if len(positions) == len(self.joints):
            target = self.target
            before = (self.reference or target).pose()
            known = {n: v for n, v in zip(self.joints, positions) if n in target.joints}
            target.set_configuration(known)
            after = (self.reference or target).pose()
            target.set_pose(before * after.inverse() * target.pose())
        else:
            rospy.logerr('point[%u] in JointTrajectory has different number of joint names[%u] '
                         'and positions[%u].' % (self.index, len(self.joints), len(positions)))
        self.start += tfs
        self.index += 1

    def shutdown(self):
        close(self.sub)


PLUGINS = {
    'libgazebo_ros_joint_pose_trajectory.so': JointPoseTrajectory,
    'libgazebo_ros_planar_move.so': PlanarMove,
    'libgazebo_ros_force.so': Force,
    'libgazebo_ros_vacuum_gripper.so': VacuumGripper,
}
