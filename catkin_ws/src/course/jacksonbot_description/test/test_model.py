"""jacksonbot: xacro expansion, check_urdf, simulator checks and the tutorial's dimensions."""
import os

import numpy as np
import pytest

from my_robot_model import model_check as mc

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
XACRO = os.path.join(PKG, 'urdf', 'jacksonbot', 'jacksonbot.urdf.xacro')


@pytest.fixture(scope='module')
def urdf():
    return mc.expand_xacro(XACRO)


def test_check_urdf_and_model_checks(urdf):
    rc, out = mc.check_urdf(urdf)
    assert rc == 0, out
    assert 'root Link: base_footprint' in out
    assert mc.problems(urdf, resolve=mc.rospack_resolver()) == []


def test_links_joints_and_tutorial_dimensions(urdf):
    m = mc.parse(urdf)
    assert sorted(m.links) == sorted([
        'base_footprint', 'base_link', 'imu_link', 'camera_link', 'laser_cylinder_link', 'laser_link',
        'left_wheel_link', 'right_wheel_link', 'front_caster_link', 'back_caster_link'])
    assert m.moving_joints() == ['left_wheel_joint', 'right_wheel_joint']
    base = m.links['base_link'].find('collision/geometry/cylinder')
    assert (float(base.get('radius')), float(base.get('length'))) == (0.10, 0.12)
    for w in ('left_wheel', 'right_wheel'):
        cyl = m.links[w + '_link'].find('visual/geometry/cylinder')
        assert (float(cyl.get('radius')), float(cyl.get('length'))) == (0.032, 0.04)
        rpy = [float(v) for v in m.links[w + '_link'].find('visual/origin').get('rpy').split()]
        assert rpy == pytest.approx([np.pi / 2, 0, 0])
        assert m.joints[w + '_joint'].find('axis').get('xyz') == '0 1 0'
    for c in ('front_caster', 'back_caster'):
        assert float(m.links[c + '_link'].find('collision/geometry/sphere').get('radius')) == 0.016
        assert m.joints[c + '_joint'].get('type') == 'fixed'
    # wheels and casters reach the ground (z = 0 of base_footprint) within the 1 mm sink
    base_z = float(m.joints['base_joint'].find('origin').get('xyz').split()[2])
    for j, r in (('left_wheel_joint', 0.032), ('front_caster_joint', 0.016)):
        bottom = base_z + float(m.joints[j].find('origin').get('xyz').split()[2]) - r
        assert abs(bottom) <= 0.0011, (j, bottom)


def test_friction_for_the_simulator(urdf):
    m = mc.parse(urdf)
    mu = {g.get('reference'): (float(g.find('mu1').text), float(g.find('mu2').text)) for g in m.gazebo}
    assert mu['left_wheel_link'] == mu['right_wheel_link'] == (20.0, 20.0)
    assert mu['front_caster_link'] == mu['back_caster_link'] == (0.0, 0.0)


def test_wheel_inertia_is_rotated_with_the_wheel(urdf):
    m = mc.parse(urdf)
    inertial = m.links['left_wheel_link'].find('inertial')
    assert inertial.find('origin').get('rpy') == m.links['left_wheel_link'].find('visual/origin').get('rpy')
    I = np.diag(mc.inertia_matrix(inertial))
    assert I == pytest.approx([0.1 * (3 * 0.032 ** 2 + 0.04 ** 2) / 12] * 2 + [0.1 * 0.032 ** 2 / 2])
