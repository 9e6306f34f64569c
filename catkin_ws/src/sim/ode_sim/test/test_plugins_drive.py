"""Drive plugins on a hand-built two-wheeled robot (no roscore): distance, turning, odometry."""
import math

import numpy as np
import pytest
import rospy

from geometry_msgs.msg import Twist
from ode_sim.ros import plugins
from ode_sim.description.model import (Collision, Geometry, Inertial, Joint, Link, Model, ModelError,
                                       Physics, Plugin as PluginDesc, Surface)
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.plugins.base import PluginContext
from ode_sim.description.transforms import Pose

R = 0.1             # wheel radius
SEP = 0.4           # wheel separation


def ground():
    return Model('ground_plane', static=True, links=[Link('link', collisions=[
        Collision('c', Geometry('plane'), surface=Surface(mu1=100, mu2=50))])])


def box_inertial(m, sx, sy, sz):
    return Inertial(m, ixx=m * (sy ** 2 + sz ** 2) / 12, iyy=m * (sx ** 2 + sz ** 2) / 12,
                    izz=m * (sx ** 2 + sy ** 2) / 12)


def com_behind(inertial):
    """The chassis mass centre 5 cm behind the axle: the robot leans on its caster."""
    inertial.pose = Pose((-0.05, 0, 0))
    return inertial


def wheel(name, y):
    cyl = Geometry('cylinder', radius=R, length=0.04)
    return Link(name, pose=Pose((0, y, R)),
                inertial=Inertial(0.5, ixx=0.5 * (3 * R * R + 0.04 ** 2) / 12,
                                  iyy=0.5 * R * R / 2, izz=0.5 * (3 * R * R + 0.04 ** 2) / 12),
                collisions=[Collision('c', cyl, pose=Pose.from_xyz_rpy((0, 0, 0),
                                                                       (math.pi / 2, 0, 0)))])


def robot(name='bot', four_wheels=False, caster_mu=0.0, pose=None):
    """base_link (box, base_footprint lumped at its bottom-centre projection on the ground),
    two wheels on continuous joints about +Y, a frictionless caster ball at the back."""
    chassis = Link('base_link', pose=Pose((0, 0, 0.15)),
                   inertial=com_behind(box_inertial(5.0, 0.4, 0.3, 0.1)),
                   collisions=[Collision('body', Geometry('box', size=(0.4, 0.3, 0.1)))],
                   lumped={'base_footprint': Pose((0, 0, -0.15))})
    links = [chassis]
    joints = []
    sides = [('left_wheel', SEP / 2), ('right_wheel', -SEP / 2)]
    if four_wheels:
        sides = [('left_front', SEP / 2, 0.12), ('right_front', -SEP / 2, 0.12),
                 ('left_rear', SEP / 2, -0.12), ('right_rear', -SEP / 2, -0.12)]
    else:
        chassis.collisions.append(Collision(
            'caster', Geometry('sphere', radius=0.05), pose=Pose((-0.15, 0, -0.1)),
            surface=Surface(mu1=caster_mu, mu2=caster_mu)))
        sides = [(n, y, 0.0) for n, y in sides]
    for n, y, x in sides:
        w = wheel(n, y)
        w.pose = Pose((x, y, R))
        links.append(w)
        joints.append(Joint(n + '_joint', 'continuous', 'base_link', n,
                            anchor=np.array([x, y, R]), axis=np.array([0.0, 1, 0])))
    return Model(name, pose=pose or Pose(), links=links, joints=joints, canonical_link='base_link')


def world(physics=None, **kw):
    pw = PhysicsWorld(physics or Physics())
    pw.add_model(ground())
    m = pw.add_model(robot(**kw))
    return pw, m, PluginContext(pw, None)


def diff_drive(ctx, m, **params):
    p = {'leftJoint': 'left_wheel_joint', 'rightJoint': 'right_wheel_joint',
         'wheelSeparation': str(SEP), 'wheelDiameter': str(2 * R), 'publishTf': '1',
         'robotBaseFrame': 'base_footprint', 'updateRate': '100'}
    p.update({k: str(v) for k, v in params.items()})
    cls = plugins.lookup('libgazebo_ros_diff_drive.so')
    return cls(ctx, m, PluginDesc('dd', 'libgazebo_ros_diff_drive.so', p))


def cmd(v, w):
    t = Twist()
    t.linear.x = v
    t.angular.z = w
    return t


def run(pw, plugs, seconds):
    for _ in range(int(round(seconds / pw.dt))):
        pw.step()
        for p in plugs:
            p.update()


def yaw_of(pose):
    return pose.rpy()[2]


def test_drives_3m_in_10s_and_encoder_odometry_agrees():
    pw, m, ctx = world()
    truth = diff_drive(ctx, m)
    enc = diff_drive(ctx, m, odometrySource='encoder')
    run(pw, [truth, enc], 0.5)                      # settle on the ground
    start = m.links['base_link'].frame_pose('base_footprint').p.copy()
    enc0 = list(enc.encoder)
    truth.on_cmd_vel(cmd(0.3, 0.0))
    enc.on_cmd_vel(cmd(0.3, 0.0))
    run(pw, [truth, enc], 10.0)
    end = m.links['base_link'].frame_pose('base_footprint').p
    travelled = np.linalg.norm(end[:2] - start[:2])
    assert travelled == pytest.approx(3.0, rel=0.03)
    enc_dist = math.hypot(enc.encoder[0] - enc0[0], enc.encoder[1] - enc0[1])
    assert enc_dist == pytest.approx(travelled, rel=0.02)
    # published odometry: ground truth of base_footprint, twist in the base frame
    msg = truth.odom_pub.sent[-1]
    assert msg.header.frame_id == 'odom' and msg.child_frame_id == 'base_footprint'
    assert msg.pose.pose.position.x == pytest.approx(end[0], abs=1e-3)
    assert msg.pose.pose.position.z == pytest.approx(0.0, abs=0.01)
    assert msg.twist.twist.linear.x == pytest.approx(0.3, rel=0.03)
    assert list(msg.pose.covariance[::7]) == [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3]
    emsg = enc.odom_pub.sent[-1]
    assert emsg.twist.twist.linear.x == pytest.approx(0.3, rel=0.03)
    # persisting command: the wheel joints are still driven at v/r
    assert m.joints['left_wheel_joint'].velocity() == pytest.approx(0.3 / R, rel=0.02)


def test_frictionless_caster_turns_at_commanded_rate_left_is_ccw():
    pw, m, ctx = world()
    dd = diff_drive(ctx, m)
    run(pw, [dd], 0.3)
    dd.on_cmd_vel(cmd(0.0, 1.0))
    run(pw, [dd], 1.0)
    y0 = yaw_of(m.pose())
    run(pw, [dd], 1.0)
    turned = (yaw_of(m.pose()) - y0 + math.pi) % (2 * math.pi) - math.pi
    assert turned == pytest.approx(1.0, rel=0.05)     # positive w: counter-clockwise
    # the right wheel (at -y) runs forward, the left one backwards (noetic convention)
    assert m.joints['right_wheel_joint'].velocity() > 1.5
    assert m.joints['left_wheel_joint'].velocity() < -1.5


def test_robot_at_rest_does_not_drift():
    # the course's worlds (my_robot_simulation/worlds/*.world) run ODE quick with 150 iterations;
    # with SDF's default 50 this frictionless-caster robot creeps a few mm per minute
    pw, m, ctx = world(Physics(iters=150))
    dd = diff_drive(ctx, m, updateRate=10)
    run(pw, [dd], 0.5)
    p0 = m.links['base_link'].frame_pose('base_footprint').p.copy()
    q0 = m.joints['left_wheel_joint'].position()
    run(pw, [dd], 60.0)
    p1 = m.links['base_link'].frame_pose('base_footprint').p
    assert np.linalg.norm(p1[:2] - p0[:2]) < 0.001
    assert abs(m.joints['left_wheel_joint'].position() - q0) < 0.01    # the wheels hold


def test_publish_tf_gates_odometry_and_tf_frames():
    pw, m, ctx = world()
    sent = []

    class TF:
        def sendTransform(self, ts):
            sent.extend(ts)
    ctx.tf = TF()
    off = diff_drive(ctx, m, publishTf=0, publishWheelTF=1, publishWheelJointState=1)
    assert off.odom_pub is None
    run(pw, [off], 0.05)
    assert {(t.header.frame_id, t.child_frame_id) for t in sent} == \
        {('base_link', 'left_wheel'), ('base_link', 'right_wheel')}
    wheel_tf = [t for t in sent if t.child_frame_id == 'left_wheel'][-1]
    assert wheel_tf.transform.translation.y == pytest.approx(SEP / 2, abs=1e-3)
    assert wheel_tf.transform.translation.z == pytest.approx(R - 0.15, abs=1e-3)
    js = off.joint_state_pub.sent[-1]
    assert js.name == ['left_wheel_joint', 'right_wheel_joint'] and len(js.position) == 2
    assert not js.velocity
    sent.clear()
    on = diff_drive(ctx, m, publishOdomTF=1)
    run(pw, [on], 0.05)
    odom_tf = [t for t in sent if t.header.frame_id == 'odom']
    assert odom_tf and odom_tf[-1].child_frame_id == 'base_footprint'
    sent.clear()
    notf = diff_drive(ctx, m, publishOdomTF=0)
    run(pw, [notf], 0.05)
    assert not sent and notf.odom_pub.sent


def test_update_rate_and_defaults(monkeypatch):
    warnings, infos = [], []
    monkeypatch.setattr(rospy, 'logwarn', lambda msg, *a: warnings.append(msg % a if a else msg))
    monkeypatch.setattr(rospy, 'loginfo', lambda msg, *a: infos.append(msg % a if a else msg))
    pw, m, ctx = world()
    cls = plugins.lookup('libgazebo_ros_diff_drive.so')
    dd = cls(ctx, m, PluginDesc('dd', 'libgazebo_ros_diff_drive.so', {
        'leftJoint': 'left_wheel_joint', 'rightJoint': 'right_wheel_joint', 'legacyMode': 'false'}))
    assert (dd.wheel_separation, dd.wheel_diameter, dd.wheel_torque, dd.wheel_accel) == \
        (0.34, 0.15, 5.0, 0.0)
    assert (dd.command_topic, dd.odometry_topic, dd.odom_frame, dd.base_frame) == \
        ('cmd_vel', 'odom', 'odom', 'base_footprint')
    assert dd.publish_tf and dd.publish_odom_tf and not dd.publish_wheel_tf
    assert dd.odom_source == 'world' and dd.period == pytest.approx(0.01)
    assert dd.odom_pub.name == '/bot/odom' and dd.ns == 'bot'
    assert any('missing <publishTf>' in w for w in warnings)
    assert any('missing <wheelSeparation>' in w for w in warnings)
    assert sum('legacyMode' in i for i in infos) == 1
    run(pw, [dd], 1.0)
    assert len(dd.odom_pub.sent) == pytest.approx(100, abs=1)
    # the wheel motor is limited by wheelTorque
    assert m.joints['left_wheel_joint'].vel_cmd[1] == 5.0


def test_wheel_acceleration_ramps_the_speed():
    pw, m, ctx = world()
    dd = diff_drive(ctx, m, wheelAcceleration=0.5)
    run(pw, [dd], 0.3)
    dd.on_cmd_vel(cmd(0.5, 0.0))
    run(pw, [dd], 0.4)
    v = m.joints['left_wheel_joint'].velocity() * R
    assert 0.1 < v < 0.3                 # about 0.5 m/s^2 * 0.4 s
    run(pw, [dd], 1.5)
    assert m.joints['left_wheel_joint'].velocity() * R == pytest.approx(0.5, rel=0.03)


def test_bad_wheel_joint_and_odometry_source_are_one_line_errors():
    pw, m, ctx = world()
    with pytest.raises(ModelError, match="couldn't get wheel hinge joint named 'nope'"):
        diff_drive(ctx, m, leftJoint='nope')
    with pytest.raises(ModelError, match="odometrySource"):
        diff_drive(ctx, m, odometrySource='gps')


def test_skid_steer_drives_four_wheels():
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    m = pw.add_model(robot(four_wheels=True))
    ctx = PluginContext(pw, None)
    cls = plugins.lookup('libgazebo_ros_skid_steer_drive.so')
    sk = cls(ctx, m, PluginDesc('sk', 'libgazebo_ros_skid_steer_drive.so', {
        'leftFrontJoint': 'left_front_joint', 'rightFrontJoint': 'right_front_joint',
        'leftRearJoint': 'left_rear_joint', 'rightRearJoint': 'right_rear_joint',
        'wheelSeparation': str(SEP), 'wheelDiameter': str(2 * R)}))
    assert sk.ns == '' and sk.odom_pub.name == '/odom' and not sk.broadcast_tf
    assert (sk.torque, sk.covariance_x, sk.covariance_y, sk.covariance_yaw) == \
        (5.0, 0.0001, 0.0001, 0.01)
    run(pw, [sk], 0.3)
    x0 = m.pose().p[0]
    sk.on_cmd_vel(cmd(0.3, 0.0))
    run(pw, [sk], 2.0)
    assert m.pose().p[0] - x0 == pytest.approx(0.6, rel=0.05)
    msg = sk.odom_pub.sent[-1]
    assert msg.twist.covariance[0] == 0.0001 and msg.twist.covariance[35] == 0.01
    assert msg.twist.twist.linear.x == pytest.approx(0.3, rel=0.05)
    with pytest.raises(ModelError, match="left rear hinge joint named 'x'"):
        cls(ctx, m, PluginDesc('sk', 'libgazebo_ros_skid_steer_drive.so', {
            'leftFrontJoint': 'left_front_joint', 'rightFrontJoint': 'right_front_joint',
            'leftRearJoint': 'x'}))


def _tf_rows(transforms):
    return [(t.header.stamp.to_nsec(), t.header.frame_id, t.child_frame_id,
             round(t.transform.translation.x, 9), round(t.transform.translation.y, 9),
             round(t.transform.rotation.z, 9)) for t in transforms]


def test_one_tf_message_per_step_group_with_the_same_transforms():
    """The node sends what the plugins broadcast during one step group as one /tf message
    (rosio.TfBatch, flushed by SimNode.step_once); a listener sees the same transforms, stamps
    and frames as with one message per plugin call. Nothing is sent without a subscriber."""
    import threading
    import types
    from tf2_msgs.msg import TFMessage
    from ode_sim.engine import _core
    from ode_sim.ros.node import SimNode
    from ode_sim.ros.plugins.rosio import MemoryIO, TfBatch

    def drive_pair(tf):
        _core.set_random_seed(1)        # quickStep's constraint order: the same in both runs
        pw, m, ctx = world()
        ctx.tf = tf
        # two plugins broadcasting: odom -> base_footprint at 50 Hz, wheels at 20 Hz
        a = diff_drive(ctx, m, publishOdomTF=1, updateRate=50)
        b = diff_drive(ctx, m, publishTf=0, publishWheelTF=1, updateRate=20)
        for p in (a, b):
            p.on_cmd_vel(cmd(0.3, 0.5))
        return pw, [a, b]

    direct = []                                   # tf2_ros: one message per sendTransform call

    class Direct:
        def sendTransform(self, ts):
            direct.append(list(ts))
    pw, plugs = drive_pair(Direct())
    run(pw, plugs, 0.5)

    batch = TfBatch(MemoryIO())
    assert batch.pub.name == '/tf' and batch.pub.data_class is TFMessage
    pw2, plugs2 = drive_pair(batch)
    node = types.SimpleNamespace(_pre=[], _post=plugs2, lock=threading.RLock(), physics=pw2,
                                 step_hooks=[], before_step_hooks=[], tf=batch,
                                 publish_clock=lambda: None,
                                 _limits=[p.next_update for p in plugs2], group_limits=[])
    groups = 0
    while pw2.steps < 500:
        n = min(SimNode.group_size(node), 500 - pw2.steps)
        SimNode.step_once(node, n)
        groups += 1
    sent = batch.pub.sent
    assert groups < 500 / 5                       # really grouped
    # the odometry (every 20 ms) and wheel (every 50 ms) broadcasts of one group: one message
    stamps = sorted({call[0].header.stamp.to_nsec() for call in direct})
    assert len(stamps) >= 25 and len(direct) >= len(stamps) + 5   # 100 ms: both plugins
    assert len(sent) == len(stamps)
    assert all(isinstance(m, TFMessage) for m in sent)
    flat_direct = [t for call in direct for t in call]
    flat_sent = [t for m in sent for t in m.transforms]
    assert _tf_rows(flat_sent) == _tf_rows(flat_direct)
    for m in sent:                                 # one stamp per message: one group
        assert len({t.header.stamp for t in m.transforms}) == 1
    both = [m for m in sent if len(m.transforms) == 3]
    assert len(both) == len(direct) - len(stamps)
    assert [t.child_frame_id for t in both[0].transforms] == \
        ['base_footprint', 'left_wheel', 'right_wheel']
    # no subscriber on /tf: nothing is published, nothing piles up
    batch.pub.connections = 0
    before = len(batch.pub.sent)
    SimNode.step_once(node, 20)
    assert len(batch.pub.sent) == before and batch.pending == []


def planar_move(ctx, m, **params):
    p = {k: str(v) for k, v in params.items()}
    cls = plugins.lookup('libgazebo_ros_planar_move.so')
    return cls(ctx, m, PluginDesc('pm', 'libgazebo_ros_planar_move.so', p))


@pytest.mark.parametrize('timeout, held', [('-1', True), ('0', False), ('0.5', True)])
def test_planar_move_cmd_timeout_as_the_original(timeout, held):
    """cmdTimeout >= 0 drops a command older than it (0: a command lasts its own step only);
    a negative one never drops it."""
    pw, m, ctx = world()
    pm = planar_move(ctx, m, cmdTimeout=timeout)
    pm.on_cmd_vel(cmd(0.3, 0.2))
    pm.before_step()
    assert pm.cmd == (0.3, 0.0, 0.2)
    pw.step()
    pm.before_step()
    assert pm.cmd == ((0.3, 0.0, 0.2) if held else (0.0, 0.0, 0.0))
