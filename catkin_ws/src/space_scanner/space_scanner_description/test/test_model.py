"""chassi_bot (space scanner): xacro expansion, check_urdf, simulator checks, dimensions,
wheel joints and their velocity transmissions, sensor frames."""
import os

import pytest

from my_robot_model import model_check as mc

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
XACRO = os.path.join(PKG, 'urdf', 'chassi_bot.urdf.xacro')
# the diploma's names (figure 1.7, the Diffbot of figure 2.18): even = left, odd = right
WHEELS = ['wheel_%d_joint' % i for i in range(4)]
WHEEL_LINKS = ['left_front_wheel', 'right_front_wheel', 'left_rear_wheel', 'right_rear_wheel']


@pytest.fixture(scope='module')
def urdf():
    return mc.expand_xacro(XACRO)


def xyz(joint):
    return [float(v) for v in joint.find('origin').get('xyz').split()]


def test_check_urdf_and_model_checks(urdf):
    rc, out = mc.check_urdf(urdf)
    assert rc == 0, out
    assert 'root Link: base_footprint' in out
    assert mc.problems(urdf, resolve=mc.rospack_resolver()) == []


def test_chassis_and_wheels(urdf):
    m = mc.parse(urdf)
    assert m.moving_joints() == WHEELS
    for d in ('base_link', 'middle_deck', 'upper_link'):
        size = [float(v) for v in m.links[d].find('collision/geometry/box').get('size').split()]
        assert size[:2] == [0.26, 0.15]
    # even wheels left (+y), odd right; 0, 1 front (+x)
    for i, j in enumerate(WHEELS):
        x, y, _ = xyz(m.joints[j])
        assert (y > 0) == (i % 2 == 0) and (x > 0) == (i <= 1), j
        assert m.joints[j].find('child').get('link') == WHEEL_LINKS[i]
        assert m.joints[j].find('axis').get('xyz') == '0 1 0'
        assert m.joints[j].find('parent').get('link') == 'base_link'
    # top of the top deck about 100 mm above the ground
    top = xyz(m.joints['base_footprint_joint'])[2] + xyz(m.joints['base_part'])[2] + 0.002
    assert top == pytest.approx(0.1, abs=0.003)


def test_transmissions(urdf):
    m = mc.parse(urdf)
    found = {}
    for t in m.transmissions:
        assert t.find('type').text == 'transmission_interface/SimpleTransmission'
        joint = t.find('joint')
        assert joint.find('hardwareInterface').text == 'hardware_interface/VelocityJointInterface'
        assert float(t.find('actuator/mechanicalReduction').text) == 1.0
        assert t.find('actuator').get('name')
        found[joint.get('name')] = t.get('name')
    assert sorted(found) == WHEELS


def test_sensor_frames(urdf):
    m = mc.parse(urdf)
    for frame in ('laser_link', 'laser', 'camera_link', 'imu_link'):
        assert frame in m.links
    assert m.joints['laser_joint'].find('parent').get('link') == 'upper_link'
    assert m.joints['laser_joint'].find('child').get('link') == 'laser_link'
    assert m.joints['laser_frame_joint'].find('parent').get('link') == 'laser_link'
    # the scan plane where the office map was cut (space_scanner_simulation's make_office_map)
    z = sum(xyz(m.joints[j])[2] for j in ('base_footprint_joint', 'base_part', 'laser_joint', 'laser_frame_joint'))
    assert z == pytest.approx(0.1185)
    assert xyz(m.joints['camera_joint'])[0] == pytest.approx(0.13 - 0.0045)


def test_boxes_by_default_mesh_when_asked(urdf):
    """No mesh unless an includer sets chassis_mesh (space_scanner_simulation does)."""
    assert '<mesh' not in urdf
    m = mc.parse(urdf)
    assert m.links['upper_link'].find('visual') is not None
