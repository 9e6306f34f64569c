"""p3d and joint_state_publisher on hand-built worlds (no roscore)."""
import math

import numpy as np
import pytest

from ode_sim.ros import plugins
from ode_sim.description.model import (Collision, Geometry, Inertial, Joint, Link, Model, ModelError, Physics,
                                       Plugin as PluginDesc)
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.plugins.base import PluginContext
from ode_sim.description.transforms import Pose


def arm_model():
    """A 1 m arm on a hinge about Y at 2 m height (world-fixed), and a slider on its tip."""
    arm = Link('arm', pose=Pose((0.5, 0, 2)),
               inertial=Inertial(1.0, ixx=1e-3, iyy=1 / 12, izz=1 / 12),
               collisions=[Collision('c', Geometry('box', size=(1, 0.05, 0.05)))],
               lumped={'tip': Pose((0.5, 0, 0))})
    block = Link('block', pose=Pose((1.0, 0, 2)),
                 inertial=Inertial(0.2, ixx=1e-3, iyy=1e-3, izz=1e-3))
    return Model('arm_bot', links=[arm, block], joints=[
        Joint('hinge', 'continuous', 'world', 'arm', anchor=np.array([0.0, 0, 2]),
              axis=np.array([0.0, 1, 0])),
        Joint('slide', 'prismatic', 'arm', 'block', anchor=np.array([1.0, 0, 2]),
              axis=np.array([1.0, 0, 0]), lower=-0.1, upper=0.1)])


def world():
    pw = PhysicsWorld(Physics())
    m = pw.add_model(arm_model())
    return pw, m, PluginContext(pw, None)


def make(ctx, m, filename, **params):
    cls = plugins.lookup(filename)
    return cls(ctx, m, PluginDesc('p', filename, {k: str(v) for k, v in params.items()}))


def run(pw, plugs, seconds):
    for _ in range(int(round(seconds / pw.dt))):
        pw.step()
        for p in plugs:
            p.update()


def test_p3d_matches_the_link_pose_and_twist():
    pw, m, ctx = world()
    p3d = make(ctx, m, 'libgazebo_ros_p3d.so', bodyName='arm', topicName='arm_truth',
               updateRate=50)
    assert p3d.pub.name == '/arm_truth' and p3d.frame_name == 'world'
    run(pw, [p3d], 0.4)
    assert len(p3d.pub.sent) == pytest.approx(20, abs=1)
    msg = p3d.pub.sent[-1]
    pose = m.links['arm'].pose()
    assert msg.header.frame_id == 'world' and msg.child_frame_id == 'arm'
    assert msg.header.stamp.to_sec() == pytest.approx(pw.time, abs=0.02)
    fresh = p3d.measure()
    got = fresh.pose.pose
    np.testing.assert_allclose([got.position.x, got.position.y, got.position.z], pose.p, atol=1e-9)
    np.testing.assert_allclose([got.orientation.x, got.orientation.y, got.orientation.z,
                                got.orientation.w], pose.q, atol=1e-9)
    lin, ang = m.links['arm'].velocity()
    t = fresh.twist.twist
    np.testing.assert_allclose([t.linear.x, t.linear.y, t.linear.z], lin, atol=1e-9)
    np.testing.assert_allclose([t.angular.x, t.angular.y, t.angular.z], ang, atol=1e-9)
    assert abs(ang[1]) > 0.5                        # it really is swinging
    assert list(fresh.pose.covariance[::7]) == [0.0] * 6


def test_p3d_frame_offsets_noise_and_lumped_body():
    pw, m, ctx = world()
    run(pw, [], 0.2)
    rel = make(ctx, m, 'libgazebo_ros_p3d.so', bodyName='block', topicName='rel', frameName='arm')
    msg = rel.measure()
    expect = m.links['arm'].pose().inverse() * m.links['block'].pose()
    p = msg.pose.pose.position
    np.testing.assert_allclose([p.x, p.y, p.z], expect.p, atol=1e-6)
    off = make(ctx, m, 'libgazebo_ros_p3d.so', bodyName='tip', topicName='tip',
               xyzOffsets='1 2 3', rpyOffset='0 0 %r' % (math.pi / 2), gaussianNoise=0.5)
    msg = off.measure()
    tip = m.links['arm'].frame_pose('tip')
    p = msg.pose.pose.position
    np.testing.assert_allclose([p.x, p.y, p.z], tip.p + [1, 2, 3], atol=1e-9)
    assert abs(msg.pose.pose.orientation.z) > 0.5     # the yaw offset shows
    assert msg.pose.covariance[0] == pytest.approx(0.25)
    assert msg.twist.covariance[35] == pytest.approx(0.25)
    # published only while subscribed
    off.pub.connections = 0
    run(pw, [off], 0.05)
    assert not off.pub.sent
    with pytest.raises(ModelError, match='missing <topicName>'):
        make(ctx, m, 'libgazebo_ros_p3d.so', bodyName='arm')
    with pytest.raises(ModelError, match="no link named 'nope'"):
        make(ctx, m, 'libgazebo_ros_p3d.so', bodyName='nope', topicName='x')
    with pytest.raises(ModelError, match='<xyzOffset> must be three numbers'):
        make(ctx, m, 'libgazebo_ros_p3d.so', bodyName='arm', topicName='x', xyzOffset='1 2')


def test_joint_state_publisher_values_and_rate():
    pw, m, ctx = world()
    jsp = make(ctx, m, 'libgazebo_ros_joint_state_publisher.so', jointName='hinge, slide')
    assert jsp.pub.name == '/arm_bot/joint_states' and jsp.period == pytest.approx(0.01)
    m.joints['slide'].set_effort(0.5)
    run(pw, [jsp], 0.5)
    assert len(jsp.pub.sent) == pytest.approx(50, abs=1)
    run(pw, [], 0.001)
    msg = jsp.measure()
    assert msg.name == ['hinge', 'slide']
    assert msg.position[0] == pytest.approx(m.joints['hinge'].position())
    assert msg.position[0] > 0.3                       # gravity swung it down
    assert msg.velocity[0] == pytest.approx(m.joints['hinge'].velocity())
    assert msg.position[1] == pytest.approx(m.joints['slide'].position())
    assert len(msg.effort) == 2
    assert msg.header.stamp.to_sec() == pytest.approx(pw.time)
    js = make(ctx, m, 'libgazebo_ros_joint_state_publisher.so', jointName='hinge',
              updateRate=10, robotNamespace='/')
    assert js.pub.name == '/joint_states'             # spawn_model's usual '/': the root
    with pytest.raises(ModelError, match="couldn't get joint named 'elbow'"):
        make(ctx, m, 'libgazebo_ros_joint_state_publisher.so', jointName='hinge,elbow')
