"""ode_sim.description.sdf and ode_sim.description.resolve: SDF 1.4-1.6 worlds and models, model:// lookup, errors."""
import os

import numpy as np
import pytest

from ode_sim.description import materials
from ode_sim.description.model import ModelError
from ode_sim.description.resolve import ModelPaths, package_dir, resolve_world
from ode_sim.description.sdf import load_world, parse_sdf_model, parse_world

HERE = os.path.dirname(os.path.abspath(__file__))
FIX = os.path.join(HERE, 'fixtures', 'loaders')
MODELS = os.path.join(FIX, 'models')
WORLDS = os.path.join(FIX, 'worlds')
BAD = os.path.join(FIX, 'bad')


@pytest.fixture(autouse=True)
def model_path(monkeypatch):
    """The fixture models (sun, ground_plane, crate) come first on GAZEBO_MODEL_PATH."""
    monkeypatch.setenv('GAZEBO_MODEL_PATH', MODELS + os.pathsep + '/nonexistent/dir')


# ------------------------------------------------------------------ resolve

def test_model_paths_order_and_library():
    paths = ModelPaths()
    assert paths.roots[0] == MODELS
    assert paths.roots[-1] == os.path.join(package_dir(), 'models')
    assert package_dir().endswith(os.path.join('sim', 'ode_sim'))
    assert paths.model_dir('sun') == os.path.join(MODELS, 'sun')
    extra = ModelPaths(extra=['/tmp'])
    assert extra.roots[0] == '/tmp'


def test_model_sdf_picks_highest_version_and_default():
    paths = ModelPaths()
    assert paths.model_sdf('crate') == os.path.join(MODELS, 'crate', 'model.sdf')
    assert paths.model_sdf('sun') == os.path.join(MODELS, 'sun', 'model.sdf')


def test_resolve_uri_kinds(tmp_path):
    paths = ModelPaths()
    cube = os.path.join(MODELS, 'crate', 'meshes', 'cube.stl')
    assert paths.resolve_uri('model://crate/meshes/cube.stl') == cube
    assert paths.resolve_uri('meshes/cube.stl', os.path.join(MODELS, 'crate')) == cube
    assert paths.resolve_uri('file://' + cube) == cube
    assert paths.resolve_uri(cube) == cube
    assert paths.resolve_uri('package://ode_sim/package.xml') == \
        os.path.join(package_dir(), 'package.xml')


@pytest.mark.parametrize('uri, words', [
    ('model://no_such_model/x.stl', ['model://no_such_model', MODELS]),
    ('package://no_such_pkg_xyz/a.stl', ['package://no_such_pkg_xyz']),
    ('meshes/none.stl', ['meshes/none.stl', 'searched']),
])
def test_resolve_uri_unknown(uri, words):
    with pytest.raises(ModelError) as e:
        ModelPaths().resolve_uri(uri, FIX)
    for w in words:
        assert w in str(e.value)


def test_resolve_world(monkeypatch, tmp_path):
    (tmp_path / 'worlds').mkdir()
    (tmp_path / 'worlds' / 'mine.world').write_text('<sdf/>')
    monkeypatch.setenv('GAZEBO_RESOURCE_PATH', str(tmp_path))
    assert resolve_world('worlds/mine.world') == str(tmp_path / 'worlds' / 'mine.world')
    w = os.path.join(WORLDS, 'textbook.world')
    assert resolve_world(w) == w
    with pytest.raises(ModelError) as e:
        resolve_world('worlds/nothing.world')
    assert str(tmp_path) in str(e.value) and package_dir() in str(e.value)


# ------------------------------------------------------------------ worlds

def test_textbook_world_sdf_1_4():
    w = load_world(os.path.join(WORLDS, 'textbook.world'))
    assert w.name == 'default'
    assert w.gravity == (0.0, 0.0, -9.8)
    ph = w.physics
    assert (ph.max_step_size, ph.real_time_update_rate, ph.real_time_factor) == (0.001, 1000, 1)
    assert (ph.solver_type, ph.iters, ph.sor) == ('quick', 150, 1.4)
    assert (ph.cfm, ph.erp) == (1e-5, 0.2)
    assert ph.contact_max_correcting_vel == 2000 and ph.contact_surface_layer == 0.01
    assert w.scene.ambient == (0.4, 0.4, 0.4, 1.0) and w.scene.shadows
    assert [l.name for l in w.lights] == ['sun']
    sun = w.lights[0]
    assert sun.type == 'directional' and sun.cast_shadows
    assert np.allclose(sun.pose.p, [0, 0, 10]) and sun.direction == (-0.5, 0.1, -0.9)
    assert sun.diffuse == (0.8, 0.8, 0.8, 1.0) and sun.attenuation_range == 1000
    [ground] = w.models
    assert ground.name == 'ground_plane' and ground.static
    link = ground.links[0]
    col = link.collisions[0]
    assert col.geometry.kind == 'plane' and col.geometry.normal == (0, 0, 1)
    assert col.geometry.plane_size == (100, 100)
    assert (col.surface.mu1, col.surface.mu2) == (100, 50)
    vis = link.visuals[0]
    assert vis.material_name == 'Gazebo/Grey' and vis.color == materials.GAZEBO_MATERIALS['Gazebo/Grey']
    assert w.warnings == []


@pytest.fixture
def features():
    """features.world, loaded with the test's model path (the autouse fixture)."""
    return load_world(os.path.join(WORLDS, 'features.world'))


def test_features_world(features):
    w = features
    assert w.name == 'features' and w.gravity == (0, 0, -9.81)
    assert w.physics.max_step_size == 0.002 and w.physics.real_time_update_rate == 0
    assert w.physics.max_contacts == 10 and w.physics.solver_type == 'world'
    assert w.physics.iters == 20 and w.physics.sor == 1.3          # default kept
    assert w.scene.background == (0, 0, 0, 1) and not w.scene.shadows
    lights = {l.name: l for l in w.lights}
    assert set(lights) == {'lamp', 'spot', 'sun2'}
    assert lights['lamp'].type == 'point' and lights['lamp'].attenuation_range == 20
    assert np.allclose(lights['sun2'].pose.p, [0, 0, 20])
    assert lights['spot'].cast_shadows and lights['spot'].direction == (0, 0, -1)
    assert [p.name for p in w.plugins] == ['world_plugin'] and w.plugins[0].params == {'rate': '5'}


def test_features_world_crates(features):
    w = features
    models = {m.name: m for m in w.models}
    assert set(models) == {'crate_1', 'crate_2', 'robot'}
    c1 = models['crate_1']
    assert c1.static and np.allclose(c1.pose.p, [1, 0, 0.25])
    assert np.allclose(models['crate_2'].pose.p, [5, 5, 0.25])       # from <state>
    body = c1.links[0]
    mesh_vis, lid = body.visuals
    assert mesh_vis.geometry.kind == 'mesh'
    assert mesh_vis.geometry.filename == os.path.join(MODELS, 'crate', 'meshes', 'cube.stl')
    assert np.allclose(mesh_vis.geometry.vertices.max(axis=0), [0.5, 0.5, 0.5])
    assert mesh_vis.color == materials.GAZEBO_MATERIALS['Gazebo/Wood']
    assert lid.color == (0.2, 0.3, 0.4, 1.0)                          # diffuse wins
    assert np.allclose(lid.geometry.vertices.max(axis=0), [0.5, 0.5, 0.02])


def test_features_world_robot_links_and_sensors(features):
    models = {m.name: m for m in features.models}
    r = models['robot']
    assert r.canonical_link == 'base' and not r.static
    assert np.allclose(r.pose.p, [0, 0, 0.1])
    base = r.link('base')
    assert base.self_collide                                          # model default
    assert base.inertial.mass == 2.0 and np.allclose(base.inertial.pose.p, [0.1, 0, 0])
    assert (base.inertial.ixx, base.inertial.iyy, base.inertial.izz, base.inertial.ixy) == \
        (0.1, 0.2, 0.3, 0.01)
    col = base.collisions[0]
    assert col.name == 'body' and col.geometry.size == (0.4, 0.3, 0.1)
    assert np.allclose(col.pose.p, [0, 0, 0.05])
    s = col.surface
    assert (s.mu1, s.mu2, s.fdir1, s.slip1, s.slip2) == (0.5, 0.25, (1, 0, 0), 0.1, 0.2)
    assert (s.kp, s.kd, s.max_vel, s.min_depth) == (1e6, 10, 0.5, 0.002)
    assert (s.bounce, s.bounce_threshold) == (0.3, 0.01)
    vis = base.visuals[0]
    assert vis.geometry.kind == 'cylinder' and vis.geometry.radius == 0.1
    assert vis.geometry.length == 0.2 and vis.color == (1, 0, 0, 1)
    sensors = {x.name: x for x in base.sensors}
    lidar = sensors['lidar']
    assert lidar.type == 'ray' and lidar.link == 'base' and lidar.update_rate == 10
    assert lidar.visualize and lidar.always_on and np.allclose(lidar.pose.p, [0, 0, 0.2])
    p = lidar.params
    assert p['samples'] == 360 and p['min_angle'] == -3.14159 and p['max_angle'] == 3.14159
    assert (p['range_min'], p['range_max'], p['range_resolution']) == (0.15, 12, 0.01)
    assert (p['noise_mean'], p['noise_stddev']) == (0, 0.01) and p['v_samples'] == 1
    assert lidar.plugins[0].filename == 'libgazebo_ros_laser.so'
    assert lidar.plugins[0].params == {'topicName': '/scan', 'frameName': 'laser'}
    cam = sensors['cam'].params
    assert (cam['horizontal_fov'], cam['width'], cam['height'], cam['format']) == \
        (1.3962634, 800, 600, 'B8G8R8')
    assert (cam['near'], cam['far'], cam['noise_stddev']) == (0.02, 300, 0.007)
    imu = sensors['imu']
    assert imu.topic == 'imu_topic' and not imu.always_on
    assert imu.params['noise_stddev'] == 0.0002
    assert imu.params['linear_acceleration_noise_stddev'] == 0.017
    arm = r.link('arm')
    assert not arm.gravity
    depth = arm.sensors[0]
    assert depth.type == 'depth' and depth.params['width'] == 64
    assert depth.params['horizontal_fov'] == 1.047 and depth.params['far'] == 100  # defaults


def test_features_world_robot_joints_and_plugin(features):
    r = {m.name: m for m in features.models}['robot']
    # joints: anchor = child pose * joint pose; 1.6 axis in the joint frame (child rotated 90
    # deg about z, so x becomes y) unless use_parent_model_frame
    hinge = r.joint('hinge')
    assert (hinge.type, hinge.parent, hinge.child) == ('revolute', 'base', 'arm')
    assert np.allclose(hinge.anchor, [0.2, 0, 0.15])
    assert np.allclose(hinge.axis, [0, 1, 0])
    assert (hinge.lower, hinge.upper, hinge.effort, hinge.velocity) == (-0.5, 1.0, 3, 2)
    assert (hinge.damping, hinge.friction) == (0.1, 0.05)
    assert np.allclose((r.link('base').pose * hinge.origin).p, hinge.anchor)
    h2 = r.joint('hinge_model_frame')
    assert h2.type == 'continuous' and np.allclose(h2.axis, [1, 0, 0])
    assert h2.lower is None and h2.upper is None
    # nested model flattened
    assert r.link('gripper::finger') is not None
    assert np.allclose(r.link('gripper::finger').pose.p, [0.5, 0, 0.1])
    slide = r.joint('gripper::slide')
    assert slide.parent == 'gripper::finger' and slide.child == 'gripper::tip'
    assert slide.type == 'prismatic' and (slide.lower, slide.upper) == (0, 0.04)
    assert r.joint('to_gripper').child == 'gripper::finger'
    anchor = r.joint('anchor')
    assert anchor.type == 'ball' and anchor.parent == 'world'
    drive = r.plugins[0]
    assert drive.name == 'drive' and drive.filename == 'libgazebo_ros_diff_drive.so'
    assert drive.params['wheelSeparation'] == '0.3' and drive.params['commandTopic'] == 'cmd_vel'
    assert drive.element.find('nested/deep').text == '1'
    assert drive.source.startswith(os.path.join(WORLDS, 'features.world') + ':')


def test_axis_1_4_is_in_the_model_frame():
    w = load_world(os.path.join(WORLDS, 'axis_1_4.world'))
    assert w.gravity == (0, 0, -3.7)                 # world-level gravity accepted in 1.4 too
    j = w.models[0].joint('j')
    assert np.allclose(j.axis, [1, 0, 0]) and np.allclose(j.anchor, [0, 0, 1])
    # the same model as SDF 1.6: the axis turns with the child link
    text = open(os.path.join(WORLDS, 'axis_1_4.world')).read().replace('"1.4"', '"1.6"')
    j6 = parse_world(text, 'axis16.world').models[0].joint('j')
    assert np.allclose(j6.axis, [0, 1, 0])


def test_spawn_sdf_model_and_unknown_material():
    text = open(os.path.join(WORLDS, 'spawn_model.sdf')).read()
    m = parse_sdf_model(text, '/gazebo/spawn_sdf_model', name='ball_2')
    assert m.name == 'ball_2' and m.canonical_link == 'ball_link'
    assert np.allclose(m.pose.p, [0, 0, 1])
    vis = m.links[0].visuals[0]
    assert vis.color == materials.GREY and vis.material_name == 'Gazebo/NoSuchColour'
    assert any('Gazebo/NoSuchColour' in w for w in m.warnings)


def test_include_overrides_static_and_name():
    text = '''<sdf version="1.6"><world name="w">
      <include><uri>model://crate</uri><static>false</static><name>loose</name></include>
      <include><uri>model://crate</uri></include>
      <include><uri>model://crate</uri></include>
    </world></sdf>'''
    w = parse_world(text, 'inc.world')
    assert [m.name for m in w.models] == ['loose', 'crate']
    assert not w.models[0].static and w.models[1].static
    assert any("'crate' already exists" in x for x in w.warnings)


def test_materials_table():
    assert materials.material_color('Gazebo/Red') == (1.0, 0.0, 0.0, 1.0)
    assert materials.material_color('Gazebo/Orange') == (1.0, 0.5088, 0.0468, 1.0)
    assert materials.material_color('Gazebo/GreenTransparent')[3] == 0.5
    warns = []
    assert materials.material_color('Gazebo/Nope', warns, 'x.urdf:3') == materials.GREY
    assert warns == ["x.urdf:3: unknown material 'Gazebo/Nope', drawn grey "
                     "(known: Gazebo/Red, Gazebo/Grey, ...)"]


# ------------------------------------------------------------------ bad input

@pytest.mark.parametrize('name, line, words', [
    ('malformed.world', 4, ['malformed XML', 'mismatched tag']),
    ('unknown_joint_link.sdf', 3, ["unknown link 'ghost'", "joint 'j'"]),
    ('screw_joint.sdf', 3, ["'screw'", 'not supported']),
    ('relative_to.sdf', 3, ["relative_to/frame='a'", 'parent frame']),
    ('bad_pose.sdf', 2, ['<pose> must be 6 numbers']),
    ('include_no_uri.world', 2, ['<include> needs <uri>']),
    ('unknown_model.world', 2, ['model://no_such_model', 'not found', MODELS]),
    ('heightmap.sdf', 2, ['<heightmap> geometry is not supported']),
    ('dae_collision.sdf', 2, ['thing.dae', 'cannot read: Collada: File came out empty']),
    ('zero_mass.sdf', 2, ["<link name='a'>", 'zero mass']),
    ('bad_number.world', 2, ['<max_step_size> must be 1 number', "'fast'"]),
    ('no_world.world', 1, ['no <world>']),
])
def test_bad_sdf_one_line(name, line, words):
    path = os.path.join(BAD, name)
    with pytest.raises(ModelError) as e:
        if name.endswith('.world'):
            load_world(path)
        else:
            parse_sdf_model(open(path).read(), path)
    msg = str(e.value)
    assert '\n' not in msg
    assert msg.startswith('%s:%d: ' % (path, line)), msg
    for w in words:
        assert w in msg, msg


def test_missing_world_file():
    with pytest.raises(ModelError, match='cannot read world file'):
        load_world('/no/such.world')


def test_include_inside_a_model_is_flattened():
    text = '''<sdf version="1.6"><model name="cart">
      <link name="deck"><inertial><mass>1</mass></inertial></link>
      <include><uri>model://crate</uri><name>load</name><pose>0 0 0.5 0 0 0</pose></include>
      <joint name="strap" type="fixed"><parent>deck</parent><child>load::body</child></joint>
    </model></sdf>'''
    m = parse_sdf_model(text, 'cart.sdf')
    assert [l.name for l in m.links] == ['deck', 'load::body']
    assert np.allclose(m.link('load::body').pose.p, [0, 0, 0.5])
    assert m.link('load::body').visuals[0].geometry.kind == 'mesh'
    assert m.joint('strap').child == 'load::body'
    assert any("nested static model 'load'" in w for w in m.warnings)
