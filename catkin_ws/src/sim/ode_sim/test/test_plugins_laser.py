"""libgazebo_ros_laser.so / libgazebo_ros_gpu_laser.so on a hand-built room (no roscore, fake
publishers), and one run against a real roscore with a rospy subscriber."""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest
import rospy

from ode_sim.ros import plugins
from ode_sim.description.model import (Collision, Geometry, Inertial, Link, Model, ModelError, Physics,
                                       Plugin as PluginDesc, Sensor, Visual, World)
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.plugins import laser as laser_plugin
from ode_sim.ros.plugins.base import PluginContext
from ode_sim.ros.plugins.rosio import SENSOR_QUEUE, MemoryPublisher, RosIO
from ode_sim.description.transforms import Pose

# sensor origin on the robot link; the robot stands at the world origin (yaw 0) at z = 0.5
SENSOR_XYZ = (0.1, 0.0, 0.2)
# wall faces seen from the world origin: +X at 3.0, +Y at 2.0, -Y at 1.0, -X open
WALLS = {'east': ((3.1, 0, 1), (0.2, 10, 2)), 'north': ((0, 2.1, 1), (10, 0.2, 2)),
         'south': ((0, -1.1, 1), (10, 0.2, 2))}


@pytest.fixture(autouse=True)
def fake_publishers(monkeypatch):
    # no rospy node here: plugins get MemoryPublishers; nobody subscribes until a test says so
    monkeypatch.setattr(MemoryPublisher, 'DEFAULT_CONNECTIONS', 0)


def room():
    links = []
    for name, (xyz, size) in WALLS.items():
        g = Geometry('box', size=size)
        links.append(Link(name, pose=Pose(xyz), collisions=[Collision('c', g)],
                          visuals=[Visual('v', g, color=(0.8, 0.8, 0.8, 1))]))
    return Model('room', static=True, links=links)


def scan_params(**kw):
    p = {'samples': 361, 'resolution': 1.0, 'min_angle': -math.pi, 'max_angle': math.pi,
         'range_min': 0.1, 'range_max': 10.0, 'range_resolution': 0.01,
         'noise_mean': 0.0, 'noise_stddev': 0.0}
    p.update(kw)
    return p


def robot(yaw=0.0, sensor_type='ray', update_rate=10.0, plugin='libgazebo_ros_laser.so',
          tags=None, sensor_link='base_link', **scan):
    """A floating (no gravity) link with a 10 cm box collision and the lidar on top."""
    sensor = Sensor('lidar', sensor_type, sensor_link, pose=Pose(SENSOR_XYZ),
                    update_rate=update_rate, params=scan_params(**scan))
    desc = PluginDesc('laser', plugin, dict(tags if tags is not None else
                                            {'topicName': 'scan', 'frameName': 'laser_link'}))
    sensor.plugins.append(desc)
    body = Geometry('box', size=(0.1, 0.1, 0.1))
    link = Link('base_link', inertial=Inertial(1.0, ixx=0.01, iyy=0.01, izz=0.01), gravity=False,
                collisions=[Collision('body', body)], sensors=[sensor],
                lumped={'laser_mount': Pose((0.05, 0, 0.1))})
    return Model('bot', pose=Pose.from_xyz_rpy((0, 0, 0.5), (0, 0, yaw)), links=[link]), sensor, desc


def setup(**kw):
    io = kw.pop('io', None)     # not a parameter: pytest would take setup(x) for a module hook
    pw = PhysicsWorld(Physics())
    pw.add_model(room())
    desc, sensor, pdesc = robot(**kw)
    m = pw.add_model(desc)
    ctx = PluginContext(pw, World(), io=io)
    cls = plugins.lookup(pdesc.filename)
    return pw, ctx, cls(ctx, m, pdesc, sensor)


def index_of(yaw_deg):
    return int(round(yaw_deg + 180))


def test_registry_has_both_laser_plugins():
    assert plugins.lookup('libgazebo_ros_laser.so') is laser_plugin.LaserPlugin
    assert plugins.lookup('libgazebo_ros_gpu_laser.so') is laser_plugin.LaserPlugin


def test_ranges_to_walls_at_known_distances():
    pw, ctx, p = setup()
    p.pub.connections = 1
    pw.step(1)
    p.update()
    assert len(p.pub.sent) == 1
    msg = p.pub.sent[0]
    r = np.array(msg.ranges)
    assert len(r) == 361
    sx = SENSOR_XYZ[0]
    assert r[index_of(0)] == pytest.approx(3.0 - sx, abs=0.01)
    assert r[index_of(90)] == pytest.approx(2.0, abs=0.01)
    assert r[index_of(-90)] == pytest.approx(1.0, abs=0.01)
    # 45 degrees towards the north wall: 2 m across, hits at 2 / sin(45)
    assert r[index_of(45)] == pytest.approx(2.0 / math.sin(math.pi / 4), abs=0.01)
    # -X is open: nothing within range_max -> +inf (REP 117, as Gazebo publishes it)
    assert math.isinf(r[0]) and r[0] > 0
    assert math.isinf(r[-1]) and r[-1] > 0
    assert r[index_of(180)] == math.inf
    assert all(math.isfinite(v) or v == math.inf for v in r)


def test_message_frame_angles_limits_and_stamp():
    pw, ctx, p = setup()
    p.pub.connections = 1
    pw.step(250)
    p.update()
    msg = p.pub.sent[-1]
    assert p.pub.name == '/scan' and p.pub.queue_size == SENSOR_QUEUE   # no scan dropped
    assert msg.header.frame_id == 'laser_link'
    assert msg.header.stamp.to_sec() == pytest.approx(0.25)
    assert msg.angle_min == pytest.approx(-math.pi)
    assert msg.angle_max == pytest.approx(math.pi)
    assert msg.angle_increment == pytest.approx(math.radians(1.0))
    assert msg.time_increment == 0.0 and msg.scan_time == 0.0
    assert msg.range_min == pytest.approx(0.1) and msg.range_max == pytest.approx(10.0)
    assert len(msg.intensities) == len(msg.ranges)


def test_range_max_clips_far_walls_to_inf():
    pw, ctx, p = setup(range_max=2.5)
    p.pub.connections = 1
    p.update()
    r = np.array(p.pub.sent[-1].ranges)
    assert r[index_of(0)] == math.inf                  # 2.9 m wall beyond 2.5 m
    assert r[index_of(90)] == pytest.approx(2.0, abs=0.01)


def test_rotated_robot_and_sensor_pose_compose():
    pw, ctx, p = setup(yaw=math.pi / 2)
    p.pub.connections = 1
    p.update()
    r = np.array(p.pub.sent[-1].ranges)
    # the sensor sits at (0, 0.1) looking +Y: the north wall is 1.9 m ahead, east 3 m right
    assert r[index_of(0)] == pytest.approx(1.9, abs=0.01)
    assert r[index_of(-90)] == pytest.approx(3.0, abs=0.01)
    assert r[index_of(90)] == math.inf


def test_sensor_moves_with_its_link():
    pw, ctx, p = setup()
    p.pub.connections = 1
    m = pw.models['bot']
    m.set_pose(Pose((1.0, 0, 0.5)))
    p.update()
    assert p.pub.sent[-1].ranges[index_of(0)] == pytest.approx(1.9, abs=0.01)


def test_own_collision_is_seen_below_its_extent_as_gazebo():
    """Gazebo does not exclude the sensor's link: with range_min 0 the rays start inside the
    own 10 cm box (sensor 0.2 m above its centre: outside it) - put the sensor at the centre."""
    desc, sensor, pdesc = robot(range_min=0.0)
    sensor.pose = Pose()
    pw = PhysicsWorld(Physics())
    pw.add_model(room())
    m = pw.add_model(desc)
    p = laser_plugin.LaserPlugin(PluginContext(pw, World()), m, pdesc, sensor)
    ranges, _ = p.measure()
    assert ranges[index_of(0)] == pytest.approx(0.05, abs=0.005)
    # with range_min past the box the walls are seen
    desc, sensor, pdesc = robot(range_min=0.1)
    sensor.pose = Pose()
    pw2 = PhysicsWorld(Physics())
    pw2.add_model(room())
    m2 = pw2.add_model(desc)
    p2 = laser_plugin.LaserPlugin(PluginContext(pw2, World()), m2, pdesc, sensor)
    assert p2.measure()[0][index_of(0)] == pytest.approx(3.0, abs=0.01)


def test_publishes_only_while_subscribed_at_the_sensor_rate():
    pw, ctx, p = setup(update_rate=10.0)
    for _ in range(300):
        pw.step(1)
        p.update()
    assert p.pub.sent == []
    p.pub.connections = 2
    for _ in range(1000):                # 1 s at 1 kHz physics
        pw.step(1)
        p.update()
    assert len(p.pub.sent) == 10
    stamps = [m.header.stamp.to_sec() for m in p.pub.sent]
    assert np.diff(stamps) == pytest.approx([0.1] * 9, abs=1.5e-3)
    p.pub.connections = 0
    for _ in range(300):
        pw.step(1)
        p.update()
    assert len(p.pub.sent) == 10


def test_update_rate_zero_is_every_step():
    pw, ctx, p = setup(update_rate=0.0)
    p.pub.connections = 1
    for _ in range(20):
        pw.step(1)
        p.update()
    assert len(p.pub.sent) == 20


def test_defaults_topic_and_frame_world_slash_stripped():
    pw, ctx, p = setup(tags={})
    assert p.pub.name == '/world'
    assert p.frame_id == 'world'          # tf::resolve strips the leading '/'


def test_namespace_and_frame_resolution():
    pw, ctx, p = setup(tags={'robotNamespace': 'r1', 'topicName': 'scan', 'frameName': 'laser'})
    assert p.pub.name == '/r1/scan'
    assert p.frame_id == 'r1/laser'        # tf_prefix = the namespace, as gazebo_plugins do
    pw, ctx, p = setup(tags={'robotNamespace': '/', 'topicName': 'scan', 'frameName': '/laser'})
    assert p.pub.name == '/scan' and p.frame_id == 'laser'
    pw, ctx, p = setup(tags={'robotNamespace': '', 'topicName': '/abs/scan'})
    assert p.pub.name == '/abs/scan' and p.ns == 'bot'     # empty namespace: the model name
    assert laser_plugin.tf_resolve('/p', 'f') == 'p/f'
    assert laser_plugin.tf_resolve('', '/f') == 'f'


def test_gaussian_noise_tag_is_ignored_and_sensor_noise_used():
    pw, ctx, p = setup(tags={'topicName': 'scan', 'gaussianNoise': '0.5'})
    r = p.measure()[0]
    assert r[index_of(90)] == pytest.approx(2.0, abs=0.01)
    pw, ctx, p = setup(noise_stddev=0.05)
    p.laser.rng = np.random.default_rng(3)
    r = np.array([p.measure()[0][index_of(90)] for _ in range(200)])
    assert 0.03 < r.std() < 0.07 and r.mean() == pytest.approx(2.0, abs=0.02)


def test_gpu_laser_same_behaviour_and_sensor_on_a_lumped_frame():
    pw, ctx, p = setup(plugin='libgazebo_ros_gpu_laser.so', sensor_type='gpu_ray')
    p.pub.connections = 1
    p.update()
    assert p.pub.sent[-1].ranges[index_of(0)] == pytest.approx(2.9, abs=0.01)
    # a sensor named after a frame lumped into base_link (0.05 m ahead of it)
    pw, ctx, p = setup(sensor_link='laser_mount')
    assert p.measure()[0][index_of(0)] == pytest.approx(2.85, abs=0.01)


def test_wrong_sensor_type_is_one_clear_error():
    with pytest.raises(ModelError, match=r"libgazebo_ros_laser.so.*sensor type=\"ray\""):
        setup(sensor_type='camera')


def test_shutdown_unregisters():
    pw, ctx, p = setup()
    p.shutdown()
    assert p.pub.unregistered


# ------------------------------------------------------------------ real roscore
def _integration_main():
    """Run in a child process (ROS_MASTER_URI of the test's roscore): the plugin on a stepped
    world publishes, a rospy subscriber in this process counts; prints one JSON line."""
    import time
    from sensor_msgs.msg import LaserScan
    rospy.init_node('laser_plugin_check', disable_signals=True)
    pw, ctx, p = setup(update_rate=20.0, io=RosIO())
    got = []
    sub = rospy.Subscriber('/scan', LaserScan, got.append, queue_size=100)
    deadline = time.time() + 15
    while p.pub.get_num_connections() == 0 and time.time() < deadline:
        time.sleep(0.02)
    while len(got) < 5 and time.time() < deadline:
        pw.step(5)                     # 5 ms of sim time per 5 ms of wall time
        p.update()
        time.sleep(0.005)
    sub.unregister()
    print(json.dumps({'n': len(got), 'frame': got[0].header.frame_id if got else '',
                      'r0': got[0].ranges[180] if got else None,
                      'stamps': [m.header.stamp.to_sec() for m in got]}))


def test_real_roscore_subscriber_receives_scans(roscore):
    out = subprocess.run([sys.executable, os.path.abspath(__file__), 'integration'],
                         env=roscore.env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr[-3000:]
    res = json.loads(out.stdout.strip().splitlines()[-1])
    assert res['n'] >= 5, res
    assert res['frame'] == 'laser_link'
    assert res['r0'] == pytest.approx(2.9, abs=0.01)
    assert np.diff(res['stamps']) == pytest.approx([0.05] * (len(res['stamps']) - 1), abs=0.006)


if __name__ == '__main__' and sys.argv[1:] == ['integration']:
    _integration_main()
