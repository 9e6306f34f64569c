"""libgazebo_ros_bumper.so on the engine's contact sensor (engine/contacts.py): a 2 kg box
resting on the ground plane and a box pushed against a wall, without a master (MemoryIO), on
both step loops; the contact sensor's SDF and URDF forms; bad input; and a running sim_node
whose SDF crate and spawned URDF robot report their contacts to `rostopic echo`."""
import subprocess

import pytest

from course_testing import Proc

from ode_sim.description import urdf
from ode_sim.description.model import (Collision, Geometry, Inertial, Link, Model, ModelError,
                                       Physics, Plugin as PluginDesc, Sensor, Surface, World)
from ode_sim.description.transforms import Pose
from ode_sim.engine.contacts import MAX_STEPS
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros import plugins
from ode_sim.ros.convert import ros_time_text
from ode_sim.ros.plugins.base import NO_WORK, PluginContext
from ode_sim.ros.plugins.contact import BumperPlugin

MASS = 2.0
G = 9.8


def ground():
    return Model('ground_plane', static=True, links=[Link('link', collisions=[
        Collision('collision', Geometry('plane'), surface=Surface(mu1=100, mu2=50))])])


def wall():
    return Model('wall', static=True, links=[Link('link', pose=Pose((1.0, 0, 0.5)), collisions=[
        Collision('collision', Geometry('box', size=(0.2, 2.0, 1.0)))])])


def bot(update_rate=10.0, tags=None, collisions=('bumper',), z=0.1, x=0.0, sensor_type='contact'):
    """A 2 kg box (0.2 m) that never sleeps, its collision 'bumper' watched by the sensor."""
    sensor = Sensor('bump', sensor_type, 'base', update_rate=update_rate,
                    params={'collisions': list(collisions)})
    pdesc = PluginDesc('bumper', 'libgazebo_ros_bumper.so',
                       dict(tags if tags is not None else {'bumperTopicName': 'bumper',
                                                           'frameName': 'world'}))
    sensor.plugins.append(pdesc)
    i = MASS * 0.2 ** 2 / 6
    link = Link('base', inertial=Inertial(MASS, ixx=i, iyy=i, izz=i), sensors=[sensor],
                collisions=[Collision('bumper', Geometry('box', size=(0.2, 0.2, 0.2)))])
    m = Model('bot', pose=Pose((x, 0, z)), links=[link], allow_auto_disable=False)
    return m, sensor, pdesc


def make(core='compiled', with_wall=False, **kw):
    pw = PhysicsWorld(Physics(), core=core)
    pw.add_model(ground())
    if with_wall:
        pw.add_model(wall())
    desc, sensor, pdesc = bot(**kw)
    m = pw.add_model(desc)
    ctx = PluginContext(pw, World())
    return pw, m, ctx, plugins.lookup(pdesc.filename)(ctx, m, pdesc, sensor)


def run(pw, p, steps):
    for _ in range(steps):
        pw.step(1)
        p.update()


def by_step(states):
    out = {}
    for s in states:
        t = float(s.info.rsplit('time:', 1)[1])
        out.setdefault(round(t, 6), []).append(s)
    return out


def test_registry_and_topic_frame_defaults():
    assert plugins.lookup('libgazebo_ros_bumper.so') is BumperPlugin
    pw, m, ctx, p = make(tags={})
    assert p.pub.name == '/bumper_states' and p.pub.queue_size == 1
    assert p.frame_id == 'world'
    pw, m, ctx, p = make(tags={'robotNamespace': 'bot', 'bumperTopicName': 'bumper',
                               'frameName': 'base'})
    assert p.pub.name == '/bot/bumper' and p.frame_id == 'base'


@pytest.mark.parametrize('core', ['compiled', 'python'])
def test_resting_box_reports_its_weight_on_the_ground(core):
    pw, m, ctx, p = make(core)
    run(pw, p, 1000)                    # 1 s, standing on the ground from the start
    assert len(p.pub.sent) == 11        # 10 Hz from t = 0 (the first update at the first step)
    msg = p.pub.sent[-1]
    assert msg.header.stamp.to_sec() == pytest.approx(1.0)
    assert msg.header.frame_id == 'world'
    steps = by_step(msg.states)
    # every step of the 0.1 s since the last message: 100 of them, one state (pair) each
    assert len(steps) == 100 and all(len(v) == 1 for v in steps.values())
    assert min(steps) == pytest.approx(0.901) and max(steps) == pytest.approx(1.0)
    s = steps[max(steps)][0]
    assert s.collision1_name == 'bot::base::bumper'
    assert s.collision2_name == 'ground_plane::link::collision'
    n = len(s.wrenches)
    assert n == len(s.contact_positions) == len(s.contact_normals) == len(s.depths) == 4
    # the ground holds the box up: total force on the box = its weight, upwards
    assert s.total_wrench.force.z == pytest.approx(MASS * G, rel=1e-3)
    assert sum(w.force.z for w in s.wrenches) == pytest.approx(s.total_wrench.force.z)
    assert abs(s.total_wrench.force.x) < 1e-6 and abs(s.total_wrench.force.y) < 1e-6
    for nrm, pos, d in zip(s.contact_normals, s.contact_positions, s.depths):
        assert (nrm.x, nrm.y, nrm.z) == pytest.approx((0, 0, 1))   # moving the box up frees it
        assert abs(pos.x) == pytest.approx(0.1) and abs(pos.y) == pytest.approx(0.1)
        assert 0 <= d < 0.01
    assert s.info == ('Debug:  i:(%d/%d)     my geom:bot::base::bumper   other geom:'
                      'ground_plane::link::collision         time:1.000000000\n'
                      % (len(msg.states) - 1, len(msg.states)))


def test_both_step_loops_agree():
    totals = {}
    for core in ('compiled', 'python'):
        pw, m, ctx, p = make(core, with_wall=True, z=0.3, x=0.7)
        run(pw, p, 300)
        totals[core] = {t: sum(s.total_wrench.force.z for s in v)
                        for t, v in by_step([s for msg in p.pub.sent for s in msg.states]).items()}
    assert sorted(totals['compiled']) == sorted(totals['python'])
    for t, f in totals['compiled'].items():
        assert f == pytest.approx(totals['python'][t], rel=1e-3, abs=1e-3)


def test_push_into_a_wall_names_the_wall_and_points_away_from_it():
    pw, m, ctx, p = make(with_wall=True, x=0.75)        # 5 cm from the wall's face (x 0.9)
    body = m.links['base'].body
    run(pw, p, 50)
    for _ in range(800):
        body.addForce((30.0, 0, 0))                     # keep pushing +x
        pw.step(1)
        p.update()
    last = by_step(p.pub.sent[-1].states)
    states = last[max(last)]
    wall = [s for s in states if s.collision2_name == 'wall::link::collision']
    assert len(wall) == 1, [s.collision2_name for s in states]
    s = wall[0]
    assert all(n.x == pytest.approx(-1.0, abs=1e-6) for n in s.contact_normals)
    assert all(abs(c.x - 0.9) < 0.01 for c in s.contact_positions)    # on the wall's face
    # at rest against the wall: the wall and the ground's friction balance the push
    assert s.total_wrench.force.x < -25.0
    assert sum(st.total_wrench.force.x for st in states) == pytest.approx(-30.0, rel=0.01)


def test_no_contact_in_the_air_and_nothing_without_subscribers():
    pw, m, ctx, p = make(z=2.0)
    m.links['base'].body.setGravityMode(False)
    run(pw, p, 200)
    assert p.pub.sent and all(msg.states == [] for msg in p.pub.sent)
    pw, m, ctx, p = make()
    p.pub.connections = 0
    assert p.next_update() == NO_WORK
    run(pw, p, 300)
    assert p.pub.sent == []
    p.pub.connections = 1               # a subscriber arrives: the next message holds the
    run(pw, p, 100)                     # steps since the last (unpublished) update
    assert len(p.pub.sent) == 1 and len(by_step(p.pub.sent[0].states)) == 100


def test_keeps_at_most_the_last_100_steps_and_every_step_at_rate_zero():
    pw, m, ctx, p = make(update_rate=1.0)
    run(pw, p, 1500)
    steps = by_step(p.pub.sent[-1].states)
    assert len(steps) == MAX_STEPS and max(steps) == pytest.approx(1.0)
    pw, m, ctx, p = make(update_rate=0.0)
    assert p.next_update() is None
    run(pw, p, 20)
    assert len(p.pub.sent) == 20 and all(len(by_step(msg.states)) == 1 for msg in p.pub.sent)


def test_removed_model_stops_its_sensor():
    pw, m, ctx, p = make()
    run(pw, p, 10)
    p.shutdown()
    assert p.pub.unregistered
    pw.remove_model('bot')
    pw.step(10)
    assert pw.contacts.take(p.key) == []


def test_bad_input_is_one_clear_error():
    with pytest.raises(ModelError, match=r"no collision named 'nose' on link 'base' "
                                         r"\(its collisions: bumper\)"):
        make(collisions=('nose',))
    with pytest.raises(ModelError, match='ContactSensor'):
        make(sensor_type='ray')


URDF = '''<robot name="r">
  <link name="base_footprint"/>
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.3 0.2 0.1"/></geometry></collision>
  </link>
  <joint name="j" type="fixed"><parent link="base_footprint"/><child link="base_link"/>
    <origin xyz="0 0 0.05"/></joint>
  <gazebo reference="base_link">
    <sensor name="bumper" type="contact">
      <update_rate>20</update_rate>
      <contact><collision>base_footprint_fixed_joint_lump__base_link_collision</collision></contact>
      <plugin name="b" filename="libgazebo_ros_bumper.so"><bumperTopicName>bumper</bumperTopicName></plugin>
    </sensor>
  </gazebo>
  %s
</robot>'''


def test_urdf_contact_sensor_on_a_lumped_link_as_gazebo_names_it():
    desc = urdf.parse_urdf(URDF % '', 'test', 'robot')
    [link] = desc.links
    [s] = link.sensors
    assert s.type == 'contact' and s.link == 'base_footprint' and s.update_rate == 20
    assert s.params['collisions'] == ['base_footprint_fixed_joint_lump__base_link_collision']
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    desc.pose = Pose((0, 0, 0.0))
    desc.allow_auto_disable = False
    m = pw.add_model(desc)
    ctx = PluginContext(pw, World())
    p = plugins.lookup('libgazebo_ros_bumper.so')(ctx, m, s.plugins[0], s)
    assert p.pub.name == '/bumper'
    run(pw, p, 500)
    st = p.pub.sent[-1].states[-1]
    assert st.collision1_name == \
        'robot::base_footprint::base_footprint_fixed_joint_lump__base_link_collision'
    assert st.total_wrench.force.z == pytest.approx(9.8, rel=1e-2)


def test_sdf_contact_sensor_without_a_collision_is_an_error():
    bad = URDF.replace('<contact><collision>base_footprint_fixed_joint_lump__base_link_collision'
                       '</collision></contact>', '')
    with pytest.raises(ModelError, match=r'needs <contact><collision>'):
        urdf.parse_urdf(bad % '', 'test', 'robot')


def test_ros_time_text_as_roscpp_streams_it():
    assert ros_time_text(1.0) == '1.000000000'
    assert ros_time_text(12.3456789) == '12.345678900'


# A resting model falls asleep after 10 quiet steps and then, as in Gazebo, collides with the
# static world no more, so what `rostopic echo` sees would depend on when it subscribes: this
# crate stays awake (SDF <allow_auto_disable>), as a model whose bumper must keep reporting.
BOX_WITH_BUMPER = '''
<model name="crate"><pose>0 0 0.1 0 0 0</pose><allow_auto_disable>false</allow_auto_disable>
  <link name="link">
    <inertial><mass>2</mass><inertia><ixx>0.013</ixx><iyy>0.013</iyy><izz>0.013</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
    <sensor name="touch" type="contact">
      <update_rate>10</update_rate>
      <contact><collision>c</collision></contact>
      <plugin name="bumper" filename="libgazebo_ros_bumper.so">
        <bumperTopicName>crate_bumper</bumperTopicName>
        <frameName>world</frameName>
      </plugin>
    </sensor>
  </link>
</model>'''


def echo_once(topic, env):
    out = subprocess.run(['rostopic', 'echo', '-n', '1', topic], env=env, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout


def test_bumper_on_a_running_simulator_sdf_and_urdf(roscore, tmp_path):
    """As a user: a world with a crate carrying an SDF contact sensor, and a URDF robot with one
    spawned by spawn_model; `rostopic echo` shows what each stands on."""
    world = tmp_path / 'w.world'
    world.write_text('<?xml version="1.0"?><sdf version="1.6"><world name="default">'
                     '<include><uri>model://ground_plane</uri></include>%s</world></sdf>'
                     % BOX_WITH_BUMPER)
    robot = tmp_path / 'r.urdf'
    robot.write_text(URDF % '')
    subprocess.run(['rosparam', 'set', '/use_sim_time', 'true'], env=roscore.env, check=True,
                   timeout=120)
    node = Proc(['rosrun', 'ode_sim', 'sim_node', str(world)], env=roscore.env,
                log=str(tmp_path / 'sim.log'))
    try:
        text = echo_once('/crate_bumper', roscore.env)
        assert "frame_id: \"world\"" in text or 'frame_id: "world"' in text, text
        assert 'collision1_name: "crate::link::c"' in text, text
        assert 'collision2_name: "ground_plane::link::collision"' in text, text
        assert 'my geom:crate::link::c   other geom:ground_plane::link::collision' in text
        spawn = subprocess.run(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-file',
                                str(robot), '-model', 'robot', '-y', '1.0'],
                               env=roscore.env, capture_output=True, text=True, timeout=120)
        assert spawn.returncode == 0, spawn.stdout + spawn.stderr
        text = echo_once('/bumper', roscore.env)
        assert ('collision1_name: "robot::base_footprint::'
                'base_footprint_fixed_joint_lump__base_link_collision"') in text, text
        assert 'collision2_name: "ground_plane::link::collision"' in text, text
    finally:
        node.stop()
    assert 'Traceback' not in node.output()
