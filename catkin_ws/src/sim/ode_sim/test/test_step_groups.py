"""Step groups: running as fast as possible the node steps up to the next time a plugin has
work in one call (SimNode.group_size); the plugins then publish at the same simulated times,
with the same data, as when stepping one step at a time."""
import types


from ode_sim.description.model import Collision, Geometry, Inertial, Link, Model, Physics, Surface
from ode_sim.description.model import Plugin as PluginDesc
from ode_sim.description.transforms import Pose
from ode_sim.engine import _core
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros import plugins
from ode_sim.ros.node import MAX_GROUP, SimNode
from ode_sim.ros.plugins.base import NO_WORK, PluginContext


def node_like(pw, limits):
    return types.SimpleNamespace(physics=pw, _limits=limits, group_limits=[])


def scene():
    _core.set_random_seed(1)        # quickStep's constraint order: the same in both runs
    pw = PhysicsWorld(Physics())
    pw.add_model(Model('ground_plane', static=True, links=[Link('link', collisions=[
        Collision('c', Geometry('plane'), surface=Surface(mu1=100, mu2=50))])]))
    m = pw.add_model(Model('bot', pose=Pose((0, 0, 0.3)), links=[Link(
        'box_link', inertial=Inertial(1.0, ixx=0.01, iyy=0.01, izz=0.01),
        collisions=[Collision('c', Geometry('box', size=(0.2, 0.2, 0.2)))])]))
    ctx = PluginContext(pw, None)
    made = []
    for rate, topic in ((100, 'imu_a'), (30, 'imu_b')):        # 30 Hz: not a whole step count
        desc = PluginDesc('imu', 'libgazebo_ros_imu.so', {'bodyName': 'box_link',
                                                          'topicName': topic,
                                                          'updateRate': str(rate)})
        made.append(plugins.lookup('libgazebo_ros_imu.so')(ctx, m, desc))
    return pw, made


def stamps(p):
    return [(msg.header.stamp.to_nsec(), msg.linear_acceleration.z) for msg in p.pub.sent]


def test_group_size_stops_at_the_next_due_time_and_on_per_step_work():
    pw = PhysicsWorld(Physics())
    assert SimNode.group_size(node_like(pw, [])) == MAX_GROUP
    assert SimNode.group_size(node_like(pw, [lambda: NO_WORK])) == MAX_GROUP
    assert SimNode.group_size(node_like(pw, [lambda: None])) == 1
    assert SimNode.group_size(node_like(pw, [lambda: 0.0])) == 1         # due now
    assert SimNode.group_size(node_like(pw, [lambda: 0.01])) == 10
    assert SimNode.group_size(node_like(pw, [lambda: 0.0333333333])) == 34
    assert SimNode.group_size(node_like(pw, [lambda: 0.01, lambda: 0.004])) == 4
    pw.step(3)
    assert SimNode.group_size(node_like(pw, [lambda: 0.01])) == 7


def test_grouped_stepping_publishes_what_single_steps_publish():
    single = scene()
    pw, ps = single
    for _ in range(2000):
        pw.step(1)
        for p in ps:
            p.update()
    grouped = scene()
    pw, ps = grouped
    calls = 0
    while pw.steps < 2000:
        n = SimNode.group_size(node_like(pw, [p.next_update for p in ps]))
        n = min(n, 2000 - pw.steps)
        pw.step(n)
        calls += 1
        for p in ps:
            p.update()
    assert calls < 2000 / 5                      # really grouped
    for a, b in zip(single[1], grouped[1]):
        sa, sb = stamps(a), stamps(b)
        assert len(sa) == len(sb) and len(sa) > 50
        assert [s for s, _ in sa] == [s for s, _ in sb]
        assert [z for _, z in sa] == [z for _, z in sb]
