"""The fast paths of the simulation thread give what the general ones give: the float-tuple
rotations against the numpy Pose maths, a repeated wheel command against a full one, a robot
with skid steer, IMU and lidar stepped in StepLoop's groups against single steps, and the
publisher without rospy's per-message yield against rospy's queue rules."""
import importlib.util
import math
import os
import random

import numpy as np
import pytest

from ode_sim.description.model import (Collision, Geometry, Inertial, Link, Model,
                                       Plugin as PluginDesc, Sensor)
from ode_sim.description.transforms import (Pose, qmul, qnormalize, qrotate, qrotate_inv,
                                            quat_multiply, quat_to_matrix, yaw_of)
from ode_sim.engine import _core
from ode_sim.engine.bodies import ros_q
from ode_sim.ros import plugins
from ode_sim.ros.plugins.rosio import MemoryIO, TfBatch, _NoYieldWrite, _queued
from ode_sim.ros.stepping import StepLoop


def _sibling(name):
    """A module next to this one (pytest runs with --import-mode=importlib: no sys.path)."""
    spec = importlib.util.spec_from_file_location(
        'ode_sim_' + name, os.path.join(os.path.dirname(os.path.abspath(__file__)), name + '.py'))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


drive_test = _sibling('test_plugins_drive')   # its hand-built robot


def random_q(rng):
    q = np.array([rng.gauss(0, 1) for _ in range(4)])
    return q / np.linalg.norm(q)


def test_tuple_rotations_are_the_pose_maths():
    rng = random.Random(3)
    for _ in range(200):
        a, b = random_q(rng), random_q(rng)
        v = np.array([rng.uniform(-5, 5) for _ in range(3)])
        np.testing.assert_allclose(qmul(tuple(a), tuple(b)), quat_multiply(a, b), atol=1e-15)
        np.testing.assert_allclose(qrotate(tuple(a), tuple(v)), quat_to_matrix(a) @ v,
                                   atol=1e-13)
        np.testing.assert_allclose(qrotate_inv(tuple(a), tuple(v)), quat_to_matrix(a).T @ v,
                                   atol=1e-13)
        assert yaw_of(tuple(a)) == pytest.approx(Pose((0, 0, 0), a).rpy()[2], abs=1e-12)
        np.testing.assert_allclose(qnormalize(tuple(3 * a)), a, atol=1e-15)
        p = Pose(v, a)
        assert p.tuples() == (tuple(p.p), tuple(p.q))
        u = Pose.unit(v, a)
        assert (u.p == v).all() and (u.q == a).all()


def test_link_poses_in_tuples_are_the_numpy_poses():
    pw, m, _ = drive_test.world(four_wheels=True, pose=Pose.from_xyz_rpy((1, 2, 0), (0, 0, 1)))
    m.links['left_front'].body.setAngularVel((0.3, -2.0, 0.5))
    pw.step(50)
    for link in m.links.values():
        b = link.body
        ref = Pose(b.getPosition(), ros_q(b.getQuaternion())) * link.com.inverse()
        pose = link.pose()
        np.testing.assert_allclose(pose.p, ref.p, atol=1e-14)
        np.testing.assert_allclose(pose.q, ref.q, atol=1e-15)
        local = Pose.from_xyz_rpy((0.1, 0.2, 0.3), (0.4, -0.5, 0.6))
        _, q = link.pose_tuples(local.q)
        np.testing.assert_allclose(q, (ref * local).q, atol=1e-15)
        np.testing.assert_allclose(link.angular_velocity(), b.getAngularVel(), atol=0)
    base = m.links['base_link']
    ref = base.pose() * base.desc.lumped['base_footprint']
    fp = base.frame_pose('base_footprint')
    np.testing.assert_allclose(fp.p, ref.p, atol=1e-14)
    np.testing.assert_allclose(fp.q, ref.q, atol=1e-15)
    lin, ang = base.point_velocity(fp.p)
    rl, ra = base.velocity(fp.p)
    assert lin == tuple(rl) and ang == tuple(ra)


def skid_world():
    _core.set_random_seed(1)        # quickStep's constraint order: the same in every run
    pw, m, ctx = drive_test.world(four_wheels=True)
    sk = plugins.lookup('libgazebo_ros_skid_steer_drive.so')(ctx, m, PluginDesc(
        'sk', 'libgazebo_ros_skid_steer_drive.so', {
            'leftFrontJoint': 'left_front_joint', 'rightFrontJoint': 'right_front_joint',
            'leftRearJoint': 'left_rear_joint', 'rightRearJoint': 'right_rear_joint',
            'wheelSeparation': str(drive_test.SEP), 'wheelDiameter': str(2 * drive_test.R),
            'updateRate': '50', 'broadcastTF': '1', 'covariance_x': '0.0001',
            'covariance_y': '0.0001', 'covariance_yaw': '0.01'}))
    sk.on_cmd_vel(drive_test.cmd(0.3, 0.4))
    return pw, m, ctx, sk


def test_a_repeated_wheel_command_moves_the_robot_as_a_full_one():
    """The drive repeats its wheel targets at 50 Hz; the joints then only wake their links
    (SimJoint.set_velocity) instead of resetting the motor: the same trajectory, bit for bit."""
    runs = []
    for full in (False, True):
        pw, m, _, sk = skid_world()
        for _ in range(600):
            if full:                    # forget the command: every call takes the full path
                for j in sk.joints:
                    j.vel_cmd = None
            pw.step(1)
            sk.update()
        runs.append(([tuple(l.body.getPosition()) + tuple(l.body.getQuaternion())
                      for l in m.links.values()], [j.position() for j in sk.joints]))
    assert runs[0] == runs[1]
    assert runs[0][0][0][0] > 0.05      # it drove


def sensor_robot():
    """skid_world's robot with an IMU (100 Hz) and a lidar (10 Hz) on its chassis, and a box
    to see."""
    pw, m, ctx, sk = skid_world()
    pw.add_model(Model('crate', pose=Pose((1.5, 0.3, 0.2)), links=[Link(
        'l', inertial=Inertial(2.0, ixx=0.1, iyy=0.1, izz=0.1),
        collisions=[Collision('c', Geometry('box', size=(0.4, 0.4, 0.4)))])]))
    imu_s = Sensor('imu', 'imu', 'base_link', pose=Pose((0.05, 0, 0.05)), update_rate=100)
    imu = plugins.lookup('libgazebo_ros_imu_sensor.so')(ctx, m, PluginDesc(
        'imu', 'libgazebo_ros_imu_sensor.so', {'topicName': 'imu', 'frameName': 'imu_link',
                                               'updateRateHZ': '100', 'gaussianNoise': '0.01',
                                               'robotNamespace': '/'}), imu_s)
    ray = Sensor('lidar', 'ray', 'base_link', pose=Pose((0, 0, 0.1)), update_rate=10, params={
        'samples': 90, 'resolution': 1.0, 'min_angle': -math.pi, 'max_angle': math.pi,
        'range_min': 0.15, 'range_max': 8.0, 'range_resolution': 0.01})
    laser = plugins.lookup('libgazebo_ros_laser.so')(ctx, m, PluginDesc(
        'lidar', 'libgazebo_ros_laser.so', {'topicName': '/scan', 'frameName': 'laser'}), ray)
    return pw, m, ctx, [sk, imu, laser]


def outputs(plugs):
    sk, imu, laser = plugs
    odom = [(o.header.stamp.to_nsec(), o.pose.pose.position.x, o.pose.pose.orientation.z,
             o.twist.twist.linear.x) for o in sk.odom_pub.sent]
    imus = [(i.header.stamp.to_nsec(), i.linear_acceleration.z, i.angular_velocity.z,
             i.orientation.w) for i in imu.pub.sent]
    scans = [(s.header.stamp.to_nsec(), tuple(s.ranges)) for s in laser.pub.sent]
    return odom, imus, scans


def test_step_groups_give_the_single_steps_joint_states_odometry_imu_and_scans():
    pw, m, ctx, plugs = sensor_robot()
    for _ in range(1000):
        pw.step(1)
        for p in plugs:
            p.update()
    single = outputs(plugs), [j.position() for j in m.joints.values()], pw.time

    pw, m, ctx, plugs = sensor_robot()
    ctx.tf = TfBatch(MemoryIO())
    loop = StepLoop(pw, ctx.tf)
    loop.set_plugins(plugs)
    groups = 0
    while pw.steps < 1000:
        loop.step_once(min(loop.group_size(), 1000 - pw.steps))
        groups += 1
    grouped = outputs(plugs), [j.position() for j in m.joints.values()], pw.time
    assert groups <= 1000 / 9           # groups up to the next IMU message
    (odom, imus, scans), joints, t = single
    assert len(odom) == 51 and len(imus) == 101 and len(scans) == 11   # t = 0.001 .. 1.0
    assert min(r for _, ranges in scans for r in ranges) > 0.15
    assert grouped == single
    # the odometry transforms went out once per group that had one, with the odometry stamps
    sent = ctx.tf.pub.sent
    assert [t.transforms[0].header.stamp.to_nsec() for t in sent] == [o[0] for o in odom]


class _Conn:
    """The transport under a rospy QueuedConnection, finished: its sender thread exits at once,
    so the queue stays as written."""
    done = True

    def set_cleanup_callback(self, cb):
        self.cb = cb


def test_no_yield_write_keeps_rospys_queue_rules():
    from rospy.impl.tcpros_pubsub import QueuedConnection
    import rospy.impl.tcpros_pubsub as tp
    c = QueuedConnection(_Conn(), 2)
    c._thread.join(5)
    assert _queued(c)
    slept = []
    orig = tp.time.sleep
    tp.time.sleep = slept.append
    try:
        write = _NoYieldWrite(c)
        woken = []
        c._cond_data_available = type('Cond', (), {'notify': lambda self: woken.append(1)})()
        for data in (b'a', b'b', b'c'):
            assert write(data) is True
        assert c._queue == [b'b', b'c']         # queue 2: the oldest dropped, as rospy does
        assert len(woken) == 3 and slept == []  # the sender woken per message, no yield
        c._error = IOError('gone')
        with pytest.raises(IOError):
            write(b'd')
        assert c._error is None and c._queue == [b'b', b'c']
        c.write_data(b'e')                      # rospy's own: sleeps
        assert slept == [0]
    finally:
        tp.time.sleep = orig
    assert not _queued(object())


def test_no_transform_is_built_while_tf_has_no_subscriber():
    pw, m, ctx, sk = skid_world()
    ctx.tf = TfBatch(MemoryIO())
    built = []
    ctx.tf.sendTransform = built.append
    ctx.tf.pub.connections = 0
    for _ in range(100):
        pw.step(1)
        sk.update()
    assert built == [] and len(sk.odom_pub.sent) == 6     # odometry still goes out (t = 0.001 ..)
    ctx.tf.pub.connections = 1
    for _ in range(100):
        pw.step(1)
        sk.update()
    assert len(built) == 5 and built[0][0].child_frame_id == 'base_footprint'
