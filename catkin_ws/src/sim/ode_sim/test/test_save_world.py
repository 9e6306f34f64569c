"""ode_sim.description.save_world (Save World, no ROS): the current world written as SDF 1.6 as
Gazebo saves it, and loaded back to the same model states; spawn SDF of <include> and <light>
(sdf.parse_sdf_model / parse_sdf_light)."""
import math
import os
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from ode_sim.description import save_world, sdf, urdf
from ode_sim.description.model import ModelError
from ode_sim.description.transforms import Pose
from ode_sim.engine.physics import PhysicsWorld

HERE = os.path.dirname(os.path.abspath(__file__))
URDF_DIR = os.path.join(HERE, 'fixtures', 'loaders', 'urdf')

WORLD = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="lab">
    <physics type="ode">
      <max_step_size>0.002</max_step_size>
      <real_time_update_rate>250</real_time_update_rate>
      <max_contacts>7</max_contacts>
      <ode><solver><type>quick</type><iters>33</iters><sor>1.2</sor></solver>
        <constraints><cfm>0.0001</cfm><erp>0.3</erp><contact_max_correcting_vel>50</contact_max_correcting_vel>
          <contact_surface_layer>0.002</contact_surface_layer></constraints></ode>
    </physics>
    <gravity>0 0 -9.81</gravity>
    <scene><ambient>0.3 0.3 0.3 1</ambient><background>0.5 0.6 0.7 1</background><shadows>0</shadows></scene>
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
    <light name="lamp" type="point"><pose>1 2 3 0 0 0</pose><diffuse>0.9 0.8 0.7 1</diffuse>
      <attenuation><range>20</range><constant>0.5</constant><linear>0.1</linear><quadratic>0.01</quadratic></attenuation>
      <cast_shadows>false</cast_shadows></light>
    <include><uri>model://traffic_cone</uri><name>cone</name><pose>1 2 0 0 0 0.5</pose></include>
  </world>
</sdf>
"""

BOX = """<sdf version="1.6"><model name="unit_box"><pose>0 0 0.5 0 0 0</pose>
  <link name="link"><inertial><mass>1</mass>
      <inertia><ixx>0.166667</ixx><iyy>0.166667</iyy><izz>0.166667</izz></inertia></inertial>
    <collision name="collision"><geometry><box><size>1 1 1</size></box></geometry></collision>
    <visual name="visual"><geometry><box><size>1 1 1</size></box></geometry>
      <material><script><name>Gazebo/Grey</name><uri>file://media/materials/scripts/gazebo.material</uri></script></material></visual>
  </link></model></sdf>"""

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><inertial><mass value="5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
    <visual><geometry><box size="0.4 0.4 0.2"/></geometry></visual></link>
  <link name="arm"><inertial><origin xyz="0.25 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision></link>
  <link name="wheel"><inertial><mass value="0.2"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3" rpy="0 0 0.2"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="10" velocity="1"/></joint>
  <joint name="spin" type="continuous"><parent link="arm"/><child link="wheel"/>
    <origin xyz="0.5 0 0" rpy="1.5707963 0 0"/><axis xyz="0 0 1"/></joint>
  <gazebo reference="base"><material>Gazebo/Red</material><mu1>0.3</mu1><mu2>0.4</mu2></gazebo>
</robot>"""


@pytest.fixture
def zero_g_world(tmp_path):
    """The world above (no gravity: models stay exactly where they are put)."""
    path = tmp_path / 'lab.world'
    path.write_text(WORLD.replace('<gravity>0 0 -9.81</gravity>', '<gravity>0 0 0</gravity>'))
    return str(path)


def build(world):
    pw = PhysicsWorld(world.physics, world.gravity)
    for m in world.models:
        pw.add_model(m)
    return pw


def spawn(pw, desc, name, pose):
    desc.name = name
    desc.pose = pose
    return pw.add_model(desc)


def saved_text(world, pw):
    return save_world.world_sdf(world, list(pw.models.values()), gravity=pw.gravity,
                                sim_time=pw.time, iterations=pw.steps)


def reload(text, tmp_path):
    path = tmp_path / 'saved.world'
    path.write_text(text)
    world = sdf.load_world(str(path))
    pw = build(world)
    save_world.apply_link_states(pw.models, save_world.read_state(str(path)))
    return world, pw


def assert_same_pose(a, b, tol=1e-9):
    assert np.allclose(a.p, b.p, atol=tol), (a, b)
    assert abs(abs(float(np.dot(a.q, b.q))) - 1.0) < tol, (a, b)


def scene_of(zero_g_world):
    """The world with an inserted box, a spawned model:// include and a URDF robot whose
    joints are turned, moved around and stepped."""
    world = sdf.load_world(zero_g_world)
    pw = build(world)
    spawn(pw, sdf.parse_sdf_model(BOX, 'spawn_sdf_model(box)', name='box_1'), 'box_1',
          Pose((3, -1, 0.5)))
    spawn(pw, sdf.parse_sdf_model(
        '<sdf version="1.6"><include><uri>model://traffic_cone</uri></include></sdf>',
        'spawn_sdf_model(cone_2)', name='cone_2'), 'cone_2', Pose((-2, 0, 0)))
    spawn(pw, urdf.parse_urdf(ARM, 'spawn_urdf_model(arm)', 'arm'), 'arm',
          Pose((0, -2, 1), (0, 0, math.sin(0.15), math.cos(0.15))))
    pw.models['arm'].set_configuration({'shoulder': 0.7, 'spin': -1.1})
    pw.models['box_1'].set_pose(Pose.from_xyz_rpy((4, 4, 0.5), (0, 0, 1.0)))
    pw.remove_model('cone')
    pw.step(10)
    return world, pw


def test_round_trip_same_models_same_poses(zero_g_world, tmp_path):
    world, pw = scene_of(zero_g_world)
    text = saved_text(world, pw)
    w2, pw2 = reload(text, tmp_path)
    assert list(pw2.models) == list(pw.models) == ['ground_plane', 'box_1', 'cone_2', 'arm']
    for name, m in pw.models.items():
        m2 = pw2.models[name]
        assert_same_pose(m.pose(), m2.pose())
        for lname, link in m.links.items():
            assert_same_pose(link.pose(), m2.links[lname].pose())
    for jname in ('shoulder', 'spin'):
        assert pw2.models['arm'].joints[jname].position() == pytest.approx(
            pw.models['arm'].joints[jname].position(), abs=1e-9)
    assert pw.models['arm'].joints['shoulder'].position() == pytest.approx(0.7, abs=1e-6)
    # and saving the reloaded world gives the same models and poses again (the reloaded world
    # starts at sim time 0)
    again = saved_text(w2, pw2)
    strip = lambda t: [l for l in t.splitlines()                            # noqa: E731
                       if not any(k in l for k in ('wall_time', 'sim_time', 'iterations'))]
    assert strip(again) == strip(text)


def test_structure_as_gazebo_saves(zero_g_world):
    world, pw = scene_of(zero_g_world)
    root = ET.fromstring(saved_text(world, pw))
    assert root.tag == 'sdf' and root.get('version') == '1.6'
    w = root.find('world')
    assert w.get('name') == 'lab'
    # model:// stays an include, with its current pose
    incs = {i.findtext('name'): i for i in w.findall('include')}
    assert set(incs) == {'ground_plane', 'cone_2'}
    assert incs['cone_2'].findtext('uri') == 'model://traffic_cone'
    assert Pose.parse(incs['cone_2'].findtext('pose')).p == pytest.approx([-2, 0, 0], abs=1e-9)
    assert incs['ground_plane'].findtext('static') == '1'
    # the inserted box: its SDF again at its current pose
    models = {m.get('name'): m for m in w.findall('model')}
    assert set(models) == {'box_1', 'arm'}
    box = models['box_1']
    p = Pose.parse(box.findtext('pose'))
    assert p.p == pytest.approx([4, 4, 0.5], abs=1e-9) and p.rpy()[2] == pytest.approx(1.0)
    assert box.find('link/visual/material/script').findtext('name') == 'Gazebo/Grey'
    # the URDF robot as a full model: links, inertial, collision with surface, visual with
    # material, joints with the axis in the model frame; continuous as unlimited revolute
    arm = models['arm']
    assert [l.get('name') for l in arm.findall('link')] == ['base', 'arm', 'wheel']
    base = arm.find('link')
    assert base.findtext('inertial/mass') == '5'
    assert base.findtext('collision/surface/friction/ode/mu') == '0.3'
    assert base.findtext('collision/surface/friction/ode/mu2') == '0.4'
    assert base.find('visual/material/script').findtext('name') == 'Gazebo/Red'
    joints = {j.get('name'): j for j in arm.findall('joint')}
    assert joints['shoulder'].get('type') == 'revolute'
    assert joints['shoulder'].findtext('axis/limit/lower') == '-2'
    assert joints['spin'].get('type') == 'revolute'
    assert float(joints['spin'].findtext('axis/limit/upper')) == 1e16
    assert joints['spin'].findtext('axis/use_parent_model_frame') == '1'
    assert arm.findtext('static') == '0'
    # lights (also the included sun), physics, gravity, scene
    lights = {l.get('name'): l for l in w.findall('light')}
    assert set(lights) == {'sun', 'lamp'}
    assert lights['lamp'].get('type') == 'point'
    assert lights['lamp'].findtext('attenuation/range') == '20'
    ph = w.find('physics')
    assert ph.get('type') == 'ode' and ph.findtext('max_step_size') == '0.002'
    assert ph.findtext('real_time_update_rate') == '250'
    assert ph.findtext('ode/solver/iters') == '33'
    assert w.findtext('gravity') == '0 0 0'
    assert w.findtext('scene/background') == '0.5 0.6 0.7 1'
    # Gazebo's <state>: sim time, iterations, every model and link pose
    st = w.find('state')
    assert st.get('world_name') == 'lab'
    assert st.findtext('sim_time') == '0 20000000' and st.findtext('iterations') == '10'
    assert [m.get('name') for m in st.findall('model')] == list(pw.models)
    assert [l.get('name') for l in st.find("model[@name='arm']").findall('link')] == \
        ['base', 'arm', 'wheel']


def test_physics_scene_lights_round_trip(zero_g_world, tmp_path):
    world, pw = scene_of(zero_g_world)
    w2, _ = reload(saved_text(world, pw), tmp_path)
    assert w2.physics == world.physics
    assert w2.gravity == pytest.approx(world.gravity)
    assert w2.scene == world.scene
    assert [(l.name, l.type, l.cast_shadows, l.attenuation_range) for l in w2.lights] == \
        [(l.name, l.type, l.cast_shadows, l.attenuation_range) for l in world.lights]
    for a, b in zip(w2.lights, world.lights):
        assert_same_pose(a.pose, b.pose)
        assert a.diffuse == pytest.approx(b.diffuse) and a.direction == pytest.approx(b.direction)


def test_urdf_robot_with_plugins_sensors_meshes(tmp_path):
    """gazebo_ext.urdf (lumped links, mesh by package:// and relative path, a ray sensor with
    its plugin, a diff drive plugin): the saved model loads to the same description."""
    desc = urdf.load_urdf(os.path.join(URDF_DIR, 'gazebo_ext.urdf'), 'ext')
    desc.robot_namespace = 'bot'
    el = save_world.model_element(desc, Pose((1, 2, 0.1)))
    text = '<sdf version="1.6">%s</sdf>' % ET.tostring(el, encoding='unicode')
    back = sdf.parse_sdf_model(text, str(tmp_path / 'm.sdf'))
    assert [l.name for l in back.links] == [l.name for l in desc.links]
    for a, b in zip(desc.links, back.links):
        assert_same_pose(a.pose, b.pose)
        assert [c.name for c in a.collisions] == [c.name for c in b.collisions]
        for ca, cb in zip(a.collisions, b.collisions):
            assert ca.geometry.kind == cb.geometry.kind
            assert ca.surface == cb.surface
            if ca.geometry.kind == 'mesh':
                assert ca.geometry.filename == cb.geometry.filename
        assert [tuple(v.color) for v in a.visuals] == \
            pytest.approx([tuple(v.color) for v in b.visuals])
        assert [(s.name, s.type, s.update_rate) for s in a.sensors] == \
            [(s.name, s.type, s.update_rate) for s in b.sensors]
        for sa, sb in zip(a.sensors, b.sensors):
            assert_same_pose(sa.pose, sb.pose)
            assert [p.filename for p in sa.plugins] == [p.filename for p in sb.plugins]
            assert all(p.params.get('robotNamespace') == 'bot' for p in sb.plugins)
        if a.inertial is not None:
            assert b.inertial.mass == pytest.approx(a.inertial.mass)
            assert np.allclose(b.inertial.tensor(), a.inertial.tensor())
    assert [(j.name, j.parent, j.child) for j in back.joints] == \
        [(j.name, j.parent, j.child) for j in desc.joints]
    for a, b in zip(desc.joints, back.joints):
        assert np.allclose(a.anchor, b.anchor) and np.allclose(a.axis, b.axis)
        assert (a.lower, a.upper, a.damping) == (b.lower, b.upper, b.damping)
    assert [p.filename for p in back.plugins] == [p.filename for p in desc.plugins]
    # spawn_model's namespace where the plugin had none; gazebo_ros_control keeps its own '/'
    assert [p.params['robotNamespace'] for p in back.plugins] == \
        [p.params.get('robotNamespace', 'bot') for p in desc.plugins]
    assert '/' in [p.params['robotNamespace'] for p in back.plugins]


def test_spawn_include_and_light():
    m = sdf.parse_sdf_model('<sdf version="1.6"><include><uri>model://traffic_cone</uri>'
                            '</include></sdf>', 'spawn', name='c7')
    assert m.name == 'c7' and m.include_uri == 'model://traffic_cone' and m.links
    box = sdf.parse_sdf_model(BOX, 'spawn', name='b')
    assert box.include_uri == '' and box.sdf_element is not None
    light = sdf.parse_sdf_light('<sdf version="1.6"><light name="x" type="spot"><pose>0 0 2 0 0 0'
                                '</pose><diffuse>1 0 0 1</diffuse></light></sdf>', 'spawn',
                                name='spot_1')
    assert light.name == 'spot_1' and light.type == 'spot' and light.diffuse == (1, 0, 0, 1)
    assert light.pose.p == pytest.approx([0, 0, 2])
    sun = sdf.parse_sdf_light('<sdf version="1.6"><include><uri>model://sun</uri></include>'
                              '</sdf>', 'spawn', name='sun2')
    assert sun.name == 'sun2' and sun.type == 'directional'
    assert sdf.parse_sdf_light(BOX, 'spawn') is None
    with pytest.raises(ModelError, match='describes a light'):
        sdf.parse_sdf_model('<sdf version="1.6"><light name="l"/></sdf>', 'spawn')
    with pytest.raises(ModelError, match='model://no_such_model_xyz'):
        sdf.parse_sdf_model('<sdf version="1.6"><include><uri>model://no_such_model_xyz</uri>'
                            '</include></sdf>', 'spawn')
    with pytest.raises(ModelError, match='no <model>, <include> or <light>'):
        sdf.parse_sdf_model('<sdf version="1.6"><actor name="a"/></sdf>', 'spawn')


def test_read_state_without_state_and_bad_text(tmp_path):
    assert save_world.read_state(WORLD) == {}
    assert save_world.read_state('<sdf><world') == {}
    assert save_world.read_state(str(tmp_path / 'missing.world')) == {}


def test_number_format():
    assert save_world.num(1.0) == '1' and save_world.num(-0.0) == '0'
    assert save_world.num(1.0000000000000009) == '1' and save_world.num(0.1) == '0.1'
    assert float(save_world.num(math.pi)) == pytest.approx(math.pi, abs=1e-12)


# ------------------------------------------------------------------ the course's robots

SRC = os.path.abspath(os.path.join(HERE, '..', '..', '..'))     # catkin_ws/src


def _xacro(relpath):
    import shutil
    import subprocess
    exe = shutil.which('xacro')
    assert exe is not None, 'xacro is not on PATH: the workspace is not built or not sourced'
    out = subprocess.run([exe, os.path.join(SRC, relpath)], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    return out.stdout


@pytest.mark.parametrize('relpath', [
    'course/my_robot_simulation/urdf/diff_robot_model.urdf.xacro',
    'course/my_robot_simulation_control/urdf/diff_robot_model.urdf.xacro',
    'course/jacksonbot_description/urdf/jacksonbot/jacksonbot.urdf.xacro',
    'space_scanner/space_scanner_simulation/urdf/chassi_bot.urdf.xacro',
])
def test_course_robots_saved_and_loaded_back(relpath, zero_g_world, tmp_path):
    """The course's robots (meshes by package://, cameras, lidars, IMUs, diff drive and
    ros_control plugins) saved as full models load back with the same links, joints,
    sensors, plugins and link poses, wheels turned included."""
    world = sdf.load_world(zero_g_world)
    pw = build(world)
    desc = urdf.parse_urdf(_xacro(relpath), os.path.join(SRC, relpath), 'robot')
    robot = spawn(pw, desc, 'robot', Pose((1, 1, 0.5), (0, 0, math.sin(0.4), math.cos(0.4))))
    robot.set_configuration({j: 0.3 * (i + 1) for i, j in enumerate(robot.joints)})
    pw.step(5)
    w2, pw2 = reload(saved_text(world, pw), tmp_path)
    back = pw2.models['robot']
    assert list(back.links) == list(robot.links) and list(back.joints) == list(robot.joints)
    for name, link in robot.links.items():
        assert_same_pose(link.pose(), back.links[name].pose())
    for name, j in robot.joints.items():
        assert back.joints[name].position() == pytest.approx(j.position(), abs=1e-9)
    d2 = back.desc
    assert [(s.name, s.type) for l in d2.links for s in l.sensors] == \
        [(s.name, s.type) for l in desc.links for s in l.sensors]
    assert sorted(p.filename for p in d2.plugins) == sorted(p.filename for p in desc.plugins)
    assert sorted((p.filename, p.name) for l in d2.links for s in l.sensors for p in s.plugins) \
        == sorted((p.filename, p.name) for l in desc.links for s in l.sensors for p in s.plugins)
    assert [c.geometry.filename for l in d2.links for c in l.collisions] == \
        [c.geometry.filename for l in desc.links for c in l.collisions]


def test_inline_sdf14_model_and_relative_mesh_saved_elsewhere(tmp_path):
    """An SDF 1.4 world's inline model (joint axis in the model frame by 1.4's default, a mesh
    by a path relative to the world file) means the same in the saved 1.6 file in another
    folder."""
    import shutil
    a, b = tmp_path / 'a', tmp_path / 'b'
    (a / 'meshes').mkdir(parents=True)
    b.mkdir()
    shutil.copy(os.path.join(HERE, 'fixtures', 'loaders', 'meshes', 'cube_ascii.stl'),
                str(a / 'meshes' / 'cube.stl'))
    (a / 'w.world').write_text("""<sdf version="1.4"><world name="old"><gravity>0 0 0</gravity>
      <model name="door"><pose>1 0 0 0 0 0</pose>
        <link name="frame"><inertial><mass>5</mass></inertial>
          <collision name="c"><geometry><mesh><uri>meshes/cube.stl</uri></mesh></geometry></collision></link>
        <link name="leaf"><pose>0 0 1 0 0 1.5707963267948966</pose><inertial><mass>1</mass></inertial>
          <collision name="c"><geometry><box><size>0.1 0.8 2</size></box></geometry></collision></link>
        <joint name="hinge" type="revolute"><parent>frame</parent><child>leaf</child>
          <axis><xyz>1 0 0</xyz></axis></joint>
      </model></world></sdf>""")
    world = sdf.load_world(str(a / 'w.world'))
    pw = build(world)
    text = saved_text(world, pw)
    (b / 'saved.world').write_text(text)
    w2 = sdf.load_world(str(b / 'saved.world'))
    d1, d2 = world.models[0], w2.models[0]
    assert np.allclose(d1.joints[0].axis, [1, 0, 0]) and np.allclose(d2.joints[0].axis, [1, 0, 0])
    assert d2.links[0].collisions[0].geometry.filename == str(a / 'meshes' / 'cube.stl')
    assert 'file://' + str(a / 'meshes' / 'cube.stl') in text


def test_spawned_sdf_model_keeps_its_robot_namespace():
    text = BOX.replace('</link></model>', '</link><plugin name="p3d" filename="libgazebo_ros_p3d.so">'
                       '<bodyName>link</bodyName></plugin>'
                       '<plugin name="own" filename="libgazebo_ros_p3d.so"><robotNamespace>/x'
                       '</robotNamespace></plugin></model>')
    assert text != BOX
    desc = sdf.parse_sdf_model(text, 'spawn', name='b')
    desc.robot_namespace = '/ns1'
    el = save_world.saved_model(desc, Pose())
    assert [p.findtext('robotNamespace') for p in el.iter('plugin')] == ['/ns1', '/x']
