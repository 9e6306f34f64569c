"""my_robot_simulation: the robot expands, passes check_urdf and the simulator checks (every
link with collision and inertial), robot_diff.gazebo agrees with the geometry, the worlds
carry the textbook's parameters. No roscore needed."""
import math
import os
import xml.etree.ElementTree as ET

import pytest

from my_robot_model import model_check as mc

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
XACRO = os.path.join(PKG, 'urdf', 'diff_robot_model.urdf.xacro')


@pytest.fixture(scope='module')
def urdf():
    return mc.expand_xacro(XACRO)


def plugin(model, filename):
    for g in model.gazebo:
        for p in g.findall('plugin'):
            if p.get('filename') == filename:
                return p
    raise AssertionError('no plugin %s in the model' % filename)


def gazebo_ref(model, link):
    return [g for g in model.gazebo if g.get('reference') == link]


def test_check_urdf_and_every_link_simulatable(urdf):
    rc, out = mc.check_urdf(urdf)
    assert rc == 0 and 'root Link: base_link has 3 child(ren)' in out, out
    assert mc.problems(urdf, root_frames=(), resolve=mc.rospack_resolver()) == []
    m = mc.parse(urdf)
    for name, link in m.links.items():
        assert link.find('collision') is not None, name
        assert float(link.find('inertial/mass').get('value')) > 0, name
    assert 'package://my_robot_simulation/models/base_frame.stl' in urdf


def test_diff_drive_plugin_matches_the_model(urdf):
    m = mc.parse(urdf)
    p = plugin(m, 'libgazebo_ros_diff_drive.so')
    tags = {c.tag: (c.text or '').strip() for c in p}
    for tag in ('legacyMode', 'alwaysOn', 'updateRate', 'leftJoint', 'rightJoint', 'wheelSeparation',
                'wheelDiameter', 'wheelTorque', 'commandTopic', 'odometryTopic', 'odometryFrame',
                'robotBaseFrame', 'publishTf'):
        assert tag in tags, tag
    assert (tags['commandTopic'], tags['odometryTopic'], tags['odometryFrame'], tags['robotBaseFrame']) == \
        ('cmd_vel', 'odom', 'odom', 'base_link')
    left, right = m.joints[tags['leftJoint']], m.joints[tags['rightJoint']]
    yl = float(left.find('origin').get('xyz').split()[1])
    yr = float(right.find('origin').get('xyz').split()[1])
    assert yl > 0 > yr, 'leftJoint must be on +y'
    assert float(tags['wheelSeparation']) == pytest.approx(yl - yr)
    r = float(m.links[left.find('child').get('link')].find('collision/geometry/cylinder').get('radius'))
    assert float(tags['wheelDiameter']) == pytest.approx(2 * r)
    for j in (left, right):
        assert j.get('type') == 'continuous'
        assert j.find('limit').get('effort') == '100' and j.find('limit').get('velocity') == '100'
        assert j.find('dynamics') is not None


def test_gazebo_materials_and_frictionless_caster(urdf):
    m = mc.parse(urdf)
    for link in m.links:
        refs = gazebo_ref(m, link)
        assert any(g.findtext('material', '').startswith('Gazebo/') for g in refs), link
    caster = gazebo_ref(m, 'caster')
    assert float(caster[0].findtext('mu1')) == 0.0 and float(caster[0].findtext('mu2')) == 0.0
    assert float(gazebo_ref(m, 'wheel_left')[0].findtext('mu1')) > 0
    # the caster touches the ground together with the wheels
    wheel_r = float(m.links['wheel_left'].find('collision/geometry/cylinder').get('radius'))
    cz = float(m.joints['caster_joint'].find('origin').get('xyz').split()[2])
    cr = float(m.links['caster'].find('collision/geometry/sphere').get('radius'))
    assert cz - cr == pytest.approx(-wheel_r)


def test_inertial_macros_formulas(urdf):
    m = mc.parse(urdf)
    I = mc.inertia_matrix(m.links['caster'].find('inertial'))
    r = float(m.links['caster'].find('collision/geometry/sphere').get('radius'))
    assert I[0][0] == pytest.approx(0.4 * 0.05 * r * r)
    I = mc.inertia_matrix(m.links['wheel_left'].find('inertial'))
    # in the inertial's frame (rolled like the visual) the cylinder's axis is z: Izz = m r^2 / 2
    assert I[2][2] == pytest.approx(0.5 * 0.2 * 0.05 ** 2)
    assert m.links['wheel_left'].find('inertial/origin').get('rpy').split()[0].startswith('1.57')


def world(name):
    return ET.parse(os.path.join(PKG, 'worlds', name)).getroot()


@pytest.mark.parametrize('name', ['empty.world', 'my_scene.world'])
def test_worlds_have_the_textbook_physics(name):
    sdf = world(name)
    assert sdf.tag == 'sdf' and sdf.get('version') == '1.4'
    w = sdf.find('world')
    uris = [i.findtext('uri') for i in w.findall('include')]
    assert 'model://sun' in uris and 'model://ground_plane' in uris
    assert w.findtext('gravity').split() == ['0', '0', '-9.8']
    ph = w.find('physics')
    assert ph.get('type') == 'ode'
    assert float(ph.findtext('max_step_size')) == 0.001
    assert float(ph.findtext('real_time_update_rate')) == 1000
    s = ph.find('ode/solver')
    assert (s.findtext('type'), int(s.findtext('iters')), float(s.findtext('sor'))) == ('quick', 150, 1.4)
    c = ph.find('ode/constraints')
    assert float(c.findtext('cfm')) == 1e-5 and float(c.findtext('erp')) == 0.2


def test_scene_has_library_objects():
    w = world('my_scene.world').find('world')
    names = [i.findtext('name') for i in w.findall('include') if i.findtext('name')]
    assert len(names) >= 5 and len(set(names)) == len(names)
    for i in w.findall('include'):
        if i.findtext('pose'):
            x, y = (float(v) for v in i.findtext('pose').split()[:2])
            assert math.hypot(x, y) > 1.0, 'object %s too close to the robot' % i.findtext('name')
