"""Drive plugins: libgazebo_ros_diff_drive.so and libgazebo_ros_skid_steer_drive.so.

Tags, defaults and behaviour as gazebo_plugins (gazebo_ros_pkgs noetic-devel):

diff_drive (gazebo_ros_diff_drive.cpp; INTERFACES.md 6.5): commandTopic cmd_vel, odometryTopic
odom, odometryFrame odom, robotBaseFrame base_footprint, publishWheelTF false, publishOdomTF true,
publishWheelJointState false, publishTf true (gates odometry: topic and TF), wheelSeparation
0.34, wheelDiameter 0.15, wheelAcceleration 0 (0 = target speed at once), wheelTorque 5 (joint
fmax), updateRate 100 (0 = every step), leftJoint left_joint, rightJoint right_joint,
odometrySource world|encoder (world). legacyMode is ignored (removed in Melodic).
The last cmd_vel persists (no timeout). Wheel targets: left (v - w*sep/2)/(d/2), right
(v + w*sep/2)/(d/2), driven by the joint motor with at most wheelTorque.

skid_steer_drive (gazebo_ros_skid_steer_drive.cpp): leftFrontJoint left_front_joint,
rightFrontJoint right_front_joint, leftRearJoint left_rear_joint, rightRearJoint
right_rear_joint, wheelSeparation 0.4, wheelDiameter 0.15, torque 5, commandTopic cmd_vel,
odometryTopic odom, odometryFrame odom, robotBaseFrame base_footprint, broadcastTF false,
updateRate 100, covariance_x 0.0001, covariance_y 0.0001, covariance_yaw 0.01; robotNamespace
defaults to the root namespace. Odometry always from the ground truth.

Ground truth: the pose of the robotBaseFrame frame in the world (the link carrying it, which
may be a frame lumped into a link by a fixed joint); the model pose when the model has no such
frame. Twist: world velocity of that frame's origin rotated by its yaw; angular z from the world.
"""
import math

import rospy

from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.rosio import SENSOR_QUEUE, close, subscribed
from ode_sim.ros.convert import joint_state_msg, odometry_msg, planar_twist, transform_msg
from ode_sim.description.transforms import Pose, quat_from_rpy, yaw_of

LEFT, RIGHT = 0, 1
ODOM_POSE_COVARIANCE = {0: 1e-5, 7: 1e-5, 14: 1e12, 21: 1e12, 28: 1e12, 35: 1e-3}


class _Drive(Plugin):
    """What both drives share: cmd_vel, ground-truth base pose, odometry message, wheel motors."""

    def _set_wheels(self, joints, speeds, fmax):
        """Joint velocity targets (rad/s) with at most `fmax` (SetParam("vel"/"fmax"))."""
        for j, w in zip(joints, speeds):
            j.set_velocity(w, fmax=fmax)

    def _odometry(self, p, q, vx, vy, wz, pose_covariance=(), twist_covariance=()):
        """nav_msgs/Odometry stamped now, odom -> base frame ids (tf_prefix resolved)."""
        return odometry_msg(self.ctx.now(), self.odom_id, self.base_id, p, q, vx, vy, wz,
                            pose_covariance, twist_covariance)

    def publish_odometry(self):
        """Odometry on the odometry topic, and odom -> base TF when the plugin's tag says so
        (publishOdomTF for the diff drive, broadcastTF for the skid steer)."""
        want_msg = subscribed(self.odom_pub)
        want_tf = self.odom_tf and self.tf_wanted()
        if not (want_msg or want_tf):
            return                      # nobody listens: no message built
        msg, pose = self.odometry()
        if want_tf:
            self.send_tf([transform_msg(msg.header.stamp, msg.header.frame_id,
                                        msg.child_frame_id, pose)])
        if want_msg:
            self.odom_pub.publish(msg)

    def _setup_base(self, base_frame, odom_frame):
        self.base_frame = base_frame
        self.odom_frame = odom_frame
        self.base_id = self.tf_frame(base_frame)    # with the tf_prefix, as published
        self.odom_id = self.tf_frame(odom_frame)
        self.base_link = None
        try:
            self.base_link = self.link(base_frame)
        except Exception:
            rospy.loginfo("%s(ns = %s): model '%s' has no frame '%s': odometry follows the "
                          "model pose" % (self.label, self.ns or '/', self.model.name, base_frame))
        self.cmd = (0.0, 0.0)
        self.cmd_sub = None

    def _subscribe(self, topic):
        from geometry_msgs.msg import Twist
        self.cmd_sub = self.ctx.io.subscriber(self.topic(topic), Twist, self.on_cmd_vel,
                                              queue_size=1)

    def on_cmd_vel(self, msg):
        self.cmd = planar_twist(msg)

    def base_state(self):
        """(Pose, linear velocity, angular velocity) of the base frame, world."""
        if self.base_link is None:
            pose = self.model.pose()
            lin, ang = self.model.twist()
            return pose, lin, ang
        pose = self.base_link.frame_pose(self.base_frame)
        lin, ang = self.base_link.velocity(pose.p)
        return pose, lin, ang

    def base_tuples(self):
        """base_state() as float tuples: (p, q, linear velocity, angular velocity)."""
        if self.base_link is None:
            pose, lin, ang = self.base_state()
            p, q = pose.tuples()
            return p, q, tuple(float(v) for v in lin), tuple(float(v) for v in ang)
        p, q = self.base_link.frame_tuples(self.base_frame)
        lin, ang = self.base_link.point_velocity(p)
        return p, q, lin, ang

    def ground_truth(self):
        """(p, q, vx, vy, wz): the base's pose and its planar twist in its own heading."""
        p, q, lin, ang = self.base_tuples()
        yaw = yaw_of(q)
        c, s = math.cos(yaw), math.sin(yaw)
        return p, q, c * lin[0] + s * lin[1], c * lin[1] - s * lin[0], float(ang[2])

    def tf_wanted(self):
        """Whether transforms sent now reach anyone (TfBatch.wanted: /tf subscribed)."""
        tf = self.ctx.tf
        if tf is None:
            return False
        wanted = getattr(tf, 'wanted', None)
        return wanted() if wanted is not None else True

    def send_tf(self, transforms):
        if self.ctx.tf is not None and transforms:
            self.ctx.tf.sendTransform(transforms)


class DiffDrive(_Drive):
    """libgazebo_ros_diff_drive.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        p = self.param
        self.command_topic = p('commandTopic', 'cmd_vel')
        self.odometry_topic = p('odometryTopic', 'odom')
        odom_frame = p('odometryFrame', 'odom')
        base_frame = p('robotBaseFrame', 'base_footprint')
        self.publish_wheel_tf = p('publishWheelTF', False, bool)
        self.publish_odom_tf = p('publishOdomTF', True, bool)
        self.publish_wheel_joint_state = p('publishWheelJointState', False, bool)
        self.wheel_separation = p('wheelSeparation', 0.34, float)
        self.wheel_diameter = p('wheelDiameter', 0.15, float)
        self.wheel_accel = p('wheelAcceleration', 0.0, float)
        self.wheel_torque = p('wheelTorque', 5.0, float)
        self.set_rate(p('updateRate', 100.0, float))
        source = p('odometrySource', 'world').strip().lower()
        if source not in ('world', 'encoder'):
            raise self.error("<odometrySource> must be 'world' or 'encoder', got %r" % source)
        self.odom_source = source
        self.joints = [self._wheel('leftJoint', 'left_joint'),
                       self._wheel('rightJoint', 'right_joint')]
        if self.has('publishTf'):
            self.publish_tf = p('publishTf', True, bool)
        else:
            self.publish_tf = True
            rospy.logwarn("GazeboRosDiffDrive Plugin (ns = %s) missing <publishTf>, defaults to 1"
                          % (self.ns or '/'))
        if self.has('legacyMode'):
            rospy.loginfo("%s(ns = %s): <legacyMode> is ignored (removed from the plugin since "
                          "Melodic; wheels turn as in Noetic)" % (self.label, self.ns or '/'))
        if self.wheel_diameter <= 0:
            raise self.error("<wheelDiameter> must be positive, got %g" % self.wheel_diameter)
        self._setup_base(base_frame, odom_frame)
        self.wheel_speed = [0.0, 0.0]          # m/s targets
        self.wheel_speed_instr = [0.0, 0.0]    # m/s ramped (wheelAcceleration)
        self.encoder = [0.0, 0.0, 0.0]         # x, y, theta
        self.encoder_twist = (0.0, 0.0)
        self._last_odom = ctx.time
        self._last_update = ctx.time

        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import JointState
        self.joint_state_pub = None
        if self.publish_wheel_joint_state:
            self.joint_state_pub = self.ctx.io.publisher(self.topic('joint_states'), JointState,
                                                         1000)
        self._subscribe(self.command_topic)
        self.odom_pub = None
        if self.publish_tf:
            self.odom_pub = self.ctx.io.publisher(self.topic(self.odometry_topic), Odometry,
                                                  SENSOR_QUEUE)

    def _wheel(self, tag, default):
        name = self.param(tag, default)
        j = self.model.joints.get(name)
        if j is None:
            raise self.error("couldn't get wheel hinge joint named '%s'" % name)
        return j

    # -- per step
    def next_update(self):
        return None if self.odom_source == 'encoder' else self._next_due()

    def update(self):
        if self.odom_source == 'encoder':
            self.update_encoder()
        if not self.due():
            return
        now = self.ctx.time
        dt = now - self._last_update
        self._last_update = now
        if self.publish_tf:
            self.publish_odometry()
        if self.publish_wheel_tf:
            self.publish_wheel_transforms()
        if self.publish_wheel_joint_state:
            self.publish_joint_state()
        self.drive(dt)

    def drive(self, dt):
        v, w = self.cmd
        half = self.wheel_separation / 2.0
        self.wheel_speed = [v - w * half, v + w * half]
        r = self.wheel_diameter / 2.0
        current = [self.joints[LEFT].velocity() * r, self.joints[RIGHT].velocity() * r]
        ws = self.wheel_speed
        if self.wheel_accel == 0 or abs(ws[LEFT] - current[LEFT]) < 0.01 \
                or abs(ws[RIGHT] - current[RIGHT]) < 0.01:
            targets = ws
        else:
            step = self.wheel_accel * dt
            inst = self.wheel_speed_instr
            diff = ws[LEFT] - current[LEFT]
            inst[LEFT] += min(diff, step) if ws[LEFT] >= current[LEFT] else max(diff, -step)
            diff = ws[RIGHT] - current[RIGHT]
            inst[RIGHT] += min(diff, step) if ws[RIGHT] > current[RIGHT] else max(diff, -step)
            targets = inst
        self._set_wheels(self.joints, [t / r for t in targets], self.wheel_torque)

    def update_encoder(self):
        now = self.ctx.time
        dt = now - self._last_odom
        self._last_odom = now
        if dt <= 0:
            return
        r = self.wheel_diameter / 2.0
        b = self.wheel_separation
        sl = self.joints[LEFT].velocity() * r * dt
        sr = self.joints[RIGHT].velocity() * r * dt
        ssum, sdiff = sl + sr, sr - sl
        x, y, th = self.encoder
        dx = ssum / 2.0 * math.cos(th + sdiff / (2.0 * b))
        dy = ssum / 2.0 * math.sin(th + sdiff / (2.0 * b))
        dth = sdiff / b
        self.encoder = [x + dx, y + dy, th + dth]
        v = math.hypot(dx, dy) / dt
        self.encoder_twist = (-v if ssum < 0 else v, dth / dt)

    def odometry(self):
        """nav_msgs/Odometry as the plugin publishes it now; also returns the base Pose."""
        if self.odom_source == 'encoder':
            x, y, th = self.encoder
            pose = Pose((x, y, 0.0), quat_from_rpy(0.0, 0.0, th))
            p, q = pose.tuples()
            vx, vy, wz = self.encoder_twist[0], 0.0, self.encoder_twist[1]
        else:
            p, q, vx, vy, wz = self.ground_truth()
            pose = Pose.unit(p, q)
        return self._odometry(p, q, vx, vy, wz, ODOM_POSE_COVARIANCE.items()), pose

    @property
    def odom_tf(self):
        return self.publish_odom_tf

    def wheel_transforms(self):
        stamp = self.ctx.now()
        out = []
        for j in self.joints:
            parent_pose = j.parent.pose() if j.parent is not None else Pose()
            rel = parent_pose.inverse() * j.child.pose()
            parent = j.parent.name if j.parent is not None else 'world'
            out.append(transform_msg(stamp, self.tf_frame(parent), self.tf_frame(j.child.name),
                                     rel))
        return out

    def publish_wheel_transforms(self):
        if self.tf_wanted():
            self.send_tf(self.wheel_transforms())

    def publish_joint_state(self):
        if not subscribed(self.joint_state_pub):
            return
        self.joint_state_pub.publish(joint_state_msg(
            self.ctx.now(), [j.name for j in self.joints], [j.position() for j in self.joints]))

    def reset(self):
        super().reset()
        self.encoder = [0.0, 0.0, 0.0]
        self.encoder_twist = (0.0, 0.0)
        self.cmd = (0.0, 0.0)
        self._last_odom = self.ctx.time
        self._last_update = self.ctx.time

    def shutdown(self):
        close(self.cmd_sub, self.odom_pub, self.joint_state_pub)


class SkidSteerDrive(_Drive):
    """libgazebo_ros_skid_steer_drive.so"""

    NAMES = (('leftFrontJoint', 'left_front_joint'), ('rightFrontJoint', 'right_front_joint'),
             ('leftRearJoint', 'left_rear_joint'), ('rightRearJoint', 'right_rear_joint'))

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        # gazebo_ros_skid_steer_drive: robotNamespace defaults to the root namespace
        self.ns = self.params['robotNamespace'].strip() if self.has('robotNamespace') else ''
        p = self.param
        self.broadcast_tf = p('broadcastTF', False, bool, warn=False)
        self.joints = []
        for tag, default in self.NAMES:
            name = p(tag, default)
            j = self.model.joints.get(name)
            if j is None:
                raise self.error("couldn't get %s hinge joint named '%s'"
                                 % (tag[:-5].replace('Front', ' front').replace('Rear', ' rear')
                                    .lower(), name))
            self.joints.append(j)
        self.wheel_separation = p('wheelSeparation', 0.4, float)
        self.wheel_diameter = p('wheelDiameter', 0.15, float)
        if self.wheel_diameter <= 0:
            raise self.error("<wheelDiameter> must be positive, got %g" % self.wheel_diameter)
        self.torque = p('torque', 5.0, float)
        self.command_topic = p('commandTopic', 'cmd_vel')
        self.odometry_topic = p('odometryTopic', 'odom')
        odom_frame = p('odometryFrame', 'odom')
        base_frame = p('robotBaseFrame', 'base_footprint')
        self.set_rate(p('updateRate', 100.0, float))
        self.covariance_x = p('covariance_x', 0.0001, float)
        self.covariance_y = p('covariance_y', 0.0001, float)
        self.covariance_yaw = p('covariance_yaw', 0.01, float)
        self._setup_base(base_frame, odom_frame)
        from nav_msgs.msg import Odometry
        self._subscribe(self.command_topic)
        self.odom_pub = self.ctx.io.publisher(self.topic(self.odometry_topic), Odometry,
                                              SENSOR_QUEUE)

    def next_update(self):
        return self._next_due()

    def update(self):
        if not self.due():
            return
        self.publish_odometry()
        self.drive()

    def drive(self):
        v, w = self.cmd
        half = self.wheel_separation / 2.0
        left, right = v - w * half, v + w * half
        r = self.wheel_diameter / 2.0
        self._set_wheels(self.joints, [s / r for s in (left, right, left, right)], self.torque)

    def odometry(self):
        p, q, vx, vy, wz = self.ground_truth()
        cov = ((0, self.covariance_x), (7, self.covariance_y), (14, 1e12), (21, 1e12),
               (28, 1e12), (35, self.covariance_yaw))
        return self._odometry(p, q, vx, vy, wz, cov, cov), Pose.unit(p, q)

    @property
    def odom_tf(self):
        return self.broadcast_tf

    def shutdown(self):
        close(self.cmd_sub, self.odom_pub)


PLUGINS = {
    'libgazebo_ros_diff_drive.so': DiffDrive,
    'libgazebo_ros_skid_steer_drive.so': SkidSteerDrive,
}
