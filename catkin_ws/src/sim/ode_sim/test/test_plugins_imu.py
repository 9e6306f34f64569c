"""IMU plugins on hand-built worlds (no roscore): gravity at rest, body-frame rates, noise."""
import math

import numpy as np
import pytest

from ode_sim.ros import plugins
from ode_sim.description.model import (Collision, Geometry, Inertial, Link, Model, ModelError, Physics,
                                       Plugin as PluginDesc, Sensor, Surface)
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.plugins.base import PluginContext
from ode_sim.description.transforms import Pose


def ground():
    return Model('ground_plane', static=True, links=[Link('link', collisions=[
        Collision('c', Geometry('plane'), surface=Surface(mu1=100, mu2=50))])])


def box_model(z=0.1, gravity=True, sensor=None, rpy=(0, 0, 0)):
    s = 0.2
    link = Link('box_link', inertial=Inertial(1.0, ixx=s * s / 6, iyy=s * s / 6, izz=s * s / 6),
                collisions=[Collision('c', Geometry('box', size=(s, s, s)))], gravity=gravity,
                lumped={'imu_link': Pose.from_xyz_rpy((0, 0, 0.1), (0, 0, math.pi / 2))})
    if sensor is not None:
        link.sensors.append(sensor)
    return Model('bot', pose=Pose.from_xyz_rpy((0, 0, z), rpy), links=[link])


def world(**kw):
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    m = pw.add_model(box_model(**kw))
    return pw, m, PluginContext(pw, None)


def model_imu(ctx, m, **params):
    p = {'bodyName': 'box_link'}
    p.update({k: str(v) for k, v in params.items()})
    cls = plugins.lookup('libgazebo_ros_imu.so')
    return cls(ctx, m, PluginDesc('imu', 'libgazebo_ros_imu.so', p))


def sensor_imu(ctx, m, sensor, **params):
    p = {'frameName': 'imu_link', 'updateRateHZ': '100'}
    p.update({k: str(v) for k, v in params.items()})
    p = {k: v for k, v in p.items() if v != 'None'}
    cls = plugins.lookup('libgazebo_ros_imu_sensor.so')
    return cls(ctx, m, PluginDesc('imu', 'libgazebo_ros_imu_sensor.so', p), sensor)


def run(pw, plugs, seconds):
    for _ in range(int(round(seconds / pw.dt))):
        pw.step()
        for p in plugs:
            p.update()


def vec(v):
    return np.array([v.x, v.y, v.z])


def test_model_imu_reads_g_at_rest():
    pw, m, ctx = world()
    imu = model_imu(ctx, m)
    run(pw, [imu], 1.0)
    assert imu.pub.name == '/default_imu' and imu.ns == ''
    assert len(imu.pub.sent) == 1000                      # updateRate 0: every step
    acc = np.array([vec(msg.linear_acceleration) for msg in imu.pub.sent[-500:]])
    assert np.all(np.abs(acc[:, 2] - 9.8) < 0.05)
    assert np.all(np.abs(acc[:, :2]) < 0.05)
    msg = imu.pub.sent[-1]
    assert msg.header.frame_id == 'box_link'
    assert msg.orientation.w == pytest.approx(1.0, abs=1e-4)
    assert np.linalg.norm(vec(msg.angular_velocity)) < 1e-3


def test_free_fall_reads_zero_and_body_frame_rates():
    pw = PhysicsWorld(Physics())
    m = pw.add_model(box_model(z=5.0, rpy=(0, 0, math.pi / 2)))
    ctx = PluginContext(pw, None)
    imu = model_imu(ctx, m, frameName='imu', updateRate=100)
    m.set_twist((0, 0, 0), (1.0, 0, 0))                  # spin about world X
    run(pw, [imu], 0.1)
    assert len(imu.pub.sent) == pytest.approx(10, abs=1)
    msg = imu.pub.sent[-1]
    assert msg.header.frame_id == 'imu'
    assert np.linalg.norm(vec(msg.linear_acceleration)) < 0.05       # falling: weightless
    # the body's X axis is the world's Y, its Y the world's -X: the spin reads as -1 about Y
    np.testing.assert_allclose(vec(msg.angular_velocity), [0, -1.0, 0], atol=0.01)


def test_sensor_imu_frame_rates_and_orientation():
    sensor = Sensor('imu', 'imu', link='box_link', pose=Pose.from_xyz_rpy((0, 0, 0),
                                                                          (math.pi / 2, 0, 0)),
                    update_rate=50.0)
    pw, m, ctx = world(sensor=sensor)
    imu = sensor_imu(ctx, m, sensor, topicName='imu')
    assert imu.topic_name == '/bot/imu'
    run(pw, [imu], 1.0)
    assert len(imu.pub.sent) == pytest.approx(50, abs=1)   # the sensor's 50 Hz wins over 100
    msg = imu.pub.sent[-1]
    assert msg.header.frame_id == 'imu_link'
    # the sensor is rolled 90 deg: "up" is its +Y
    np.testing.assert_allclose(vec(msg.linear_acceleration), [0, 9.8, 0], atol=0.05)
    q = [msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w]
    np.testing.assert_allclose(np.abs(q), [math.sin(math.pi / 4), 0, 0, math.cos(math.pi / 4)],
                               atol=1e-3)
    ref = sensor_imu(ctx, m, sensor, initialOrientationAsReference='true')
    rq = ref.measure().orientation
    assert rq.w == pytest.approx(1.0, abs=1e-3)


def test_sensor_imu_defaults_namespace_and_required_frame():
    sensor = Sensor('imu', 'imu', link='box_link')
    pw, m, ctx = world(sensor=sensor)
    imu = sensor_imu(ctx, m, sensor, updateRateHZ=None)
    assert imu.topic_name == '/bot/imu_data' and imu.period == pytest.approx(1.0)
    assert sensor_imu(ctx, m, sensor, robotNamespace='/', topicName='/imu').topic_name == '/imu'
    run(pw, [imu], 2.5)
    assert len(imu.pub.sent) == 3                          # 1 Hz: t = 0, 1, 2
    with pytest.raises(ModelError, match='missing <frameName>'):
        sensor_imu(ctx, m, sensor, frameName=None)
    with pytest.raises(ModelError, match='bodyName'):
        plugins.lookup('libgazebo_ros_imu.so')(ctx, m, PluginDesc('i', 'libgazebo_ros_imu.so', {}))


def test_noise_covariance_and_only_while_subscribed():
    sensor = Sensor('imu', 'imu', link='box_link', params={'noise_stddev': 0.0})
    pw, m, ctx = world(sensor=sensor)
    imu = sensor_imu(ctx, m, sensor, gaussianNoise=0.1, updateRateHZ=0)
    run(pw, [imu], 0.5)
    acc = np.array([vec(msg.linear_acceleration) for msg in imu.pub.sent[100:]])
    assert acc[:, 0].std() == pytest.approx(0.1, rel=0.15)
    assert acc[:, 2].mean() == pytest.approx(9.8, abs=0.02)
    msg = imu.pub.sent[-1]
    assert list(msg.linear_acceleration_covariance) == pytest.approx(
        [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01])
    assert msg.orientation_covariance[4] == pytest.approx(0.01)
    n = len(imu.pub.sent)
    imu.pub.connections = 0
    run(pw, [imu], 0.1)
    assert len(imu.pub.sent) == n
