"""my_robot_model: both models expand, pass check_urdf and the simulator checks; unit tests of
the checker itself on broken models (it must be able to fail)."""
import os
import subprocess

import numpy as np
import pytest

from my_robot_model import model_check as mc

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
XACRO = os.path.join(PKG, 'urdf', 'diff_robot_model.urdf.xacro')
FIRST = os.path.join(PKG, 'urdf', 'my_first_model.urdf')


@pytest.fixture(scope='module')
def diff_robot():
    return mc.expand_xacro(XACRO)


def first_model():
    with open(FIRST) as f:
        return f.read()


def test_diff_robot_passes_check_urdf_and_model_checks(diff_robot):
    rc, out = mc.check_urdf(diff_robot)
    assert rc == 0, out
    assert 'root Link: base_link' in out
    assert mc.problems(diff_robot, resolve=mc.rospack_resolver()) == []


def test_diff_robot_structure(diff_robot):
    m = mc.parse(diff_robot)
    assert m.name == 'my_robot'
    assert sorted(m.links) == ['base_link', 'caster', 'wheel_left', 'wheel_right']
    assert m.moving_joints() == ['wheel_left_joint', 'wheel_right_joint']
    for side, sign in (('left', 1), ('right', -1)):
        j = m.joints['wheel_%s_joint' % side]
        assert j.find('axis').get('xyz') == '0 1 0'
        x, y, z = map(float, j.find('origin').get('xyz').split())
        assert (x, z) == (0.06, 0.0) and sign * y == pytest.approx(0.1175)
    mesh = m.links['base_link'].find('visual/geometry/mesh')
    assert mesh.get('filename') == 'package://my_robot_model/models/base_frame.stl'
    # the wheels and the caster touch the same ground plane
    wheel_bottom = 0.0 - float(m.links['wheel_left'].find('collision/geometry/cylinder').get('radius'))
    cz = float(m.joints['caster_joint'].find('origin').get('xyz').split()[2])
    caster_bottom = cz - float(m.links['caster'].find('collision/geometry/sphere').get('radius'))
    assert caster_bottom == pytest.approx(wheel_bottom)
    colours = mc.material_colours(diff_robot)
    assert colours['orange'] == pytest.approx((1.0, 108 / 255, 10 / 255, 1.0))
    assert m.links['base_link'].find('visual/material').get('name') == 'orange'


def test_inertia_macros_follow_the_solid_formulas(diff_robot):
    m = mc.parse(diff_robot)
    I = mc.inertia_matrix(m.links['base_link'].find('inertial'))
    assert np.diag(I) == pytest.approx([1.5 * (0.2 ** 2 + 0.05 ** 2) / 12, 1.5 * (0.3 ** 2 + 0.05 ** 2) / 12,
                                        1.5 * (0.3 ** 2 + 0.2 ** 2) / 12])
    I = mc.inertia_matrix(m.links['wheel_left'].find('inertial'))
    assert np.diag(I) == pytest.approx([0.2 * (3 * 0.05 ** 2 + 0.025 ** 2) / 12] * 2 + [0.2 * 0.05 ** 2 / 2])
    I = mc.inertia_matrix(m.links['caster'].find('inertial'))
    assert np.diag(I) == pytest.approx([0.4 * 0.05 * 0.0125 ** 2] * 3)


def test_first_model_passes_check_urdf_and_model_checks():
    text = first_model()
    rc, out = mc.check_urdf(text)
    assert rc == 0, out
    assert mc.problems(text) == []
    m = mc.parse(text)
    assert m.moving_joints() == ['wheel_left_joint', 'wheel_right_joint']


def test_first_model_matches_the_xacro_model(diff_robot):
    """The two models are the same robot: same links, joints, origins and inertias."""
    a, b = mc.parse(first_model()), mc.parse(diff_robot)
    assert sorted(a.links) == sorted(b.links) and sorted(a.joints) == sorted(b.joints)
    for n in a.joints:
        oa = [float(v) for v in a.joints[n].find('origin').get('xyz').split()]
        ob = [float(v) for v in b.joints[n].find('origin').get('xyz').split()]
        assert oa == pytest.approx(ob, abs=1e-9), n
    for n in a.links:
        assert mc.inertia_matrix(a.links[n].find('inertial')) == pytest.approx(
            mc.inertia_matrix(b.links[n].find('inertial')), rel=1e-4), n


GOOD_LINK = ('<link name="{n}"><collision><geometry><box size="1 1 1"/></geometry></collision>'
             '<inertial><mass value="1"/><inertia ixx="{i}" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>'
             '</inertial></link>')


def robot(*parts):
    return '<robot name="r">%s</robot>' % ''.join(parts)


def test_checker_reports_each_kind_of_problem():
    assert mc.problems(robot(GOOD_LINK.format(n='a', i=1))) == []
    assert mc.problems(robot('<link name="a"/>')) == ['link a: no <collision>', 'link a: no <inertial>']
    assert mc.problems(robot('<link name="base_footprint"/>')) == []   # a bare root frame
    p = mc.problems(robot(GOOD_LINK.format(n='a', i=-1)))
    assert len(p) == 1 and 'not positive definite' in p[0]
    p = mc.problems(robot(GOOD_LINK.format(n='a', i=5)))
    assert len(p) == 1 and 'triangle inequality' in p[0]
    p = mc.problems(robot(GOOD_LINK.format(n='a', i=1), GOOD_LINK.format(n='b', i=1)))
    assert p == ['the links form 2 trees (roots a, b), expected one']
    p = mc.problems(robot(GOOD_LINK.format(n='a', i=1), GOOD_LINK.format(n='b', i=1),
                          '<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>'))
    assert p == ['joint j: continuous joint needs a non-zero <axis xyz>']
    p = mc.problems(robot(GOOD_LINK.format(n='a', i=1),
                          '<joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>'))
    assert p == ["joint j: child link 'c' is not defined"]
    p = mc.problems(robot(GOOD_LINK.format(n='a', i=1).replace(
        '</link>', '<visual><geometry><mesh filename="package://nopkg/x.stl"/></geometry>'
                   '<material name="pink"/></visual></link>')), resolve=mc.package_resolver(lambda p: None))
    assert p == ['link a visual 0: mesh package://nopkg/x.stl not found',
                 "link a visual 0: material 'pink' is not defined"]
    with pytest.raises(mc.ModelError, match='not well-formed'):
        mc.problems('<robot>')


def test_check_model_cli(tmp_path):
    script = os.path.join(PKG, 'scripts', 'check_model.py')
    r = subprocess.run([script, XACRO], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and 'OK: robot my_robot, 4 links, 3 joints (2 moving)' in r.stdout, r.stdout + r.stderr
    bad = tmp_path / 'bad.urdf'
    bad.write_text(robot('<link name="a"/>'))
    r = subprocess.run([script, str(bad)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and 'link a: no <inertial>' in r.stdout
    r = subprocess.run([script, str(tmp_path / 'missing.urdf')], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and r.stderr.strip().endswith('no such file') and 'Traceback' not in r.stderr
    broken = tmp_path / 'broken.urdf.xacro'
    broken.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:nosuch/></robot>')
    r = subprocess.run([script, str(broken)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and 'xacro' in r.stderr and 'Traceback' not in r.stderr


def test_done_model_stands_on_base_link_origin(diff_robot):
    """diff_robot_model_done.urdf.xacro (the textbook's PW4 sim.launch loads it, spawned without
    -z): the same robot with base_link's origin on the ground and the diff-drive plugin."""
    text = mc.expand_xacro(os.path.join(PKG, 'urdf', 'diff_robot_model_done.urdf.xacro'))
    rc, out = mc.check_urdf(text)
    assert rc == 0, out
    assert mc.problems(text, resolve=mc.rospack_resolver()) == []
    m, pw3 = mc.parse(text), mc.parse(diff_robot)
    assert sorted(m.links) == sorted(pw3.links) and sorted(m.joints) == sorted(pw3.joints)
    r = float(m.links['wheel_left'].find('collision/geometry/cylinder').get('radius'))
    for side in ('left', 'right'):
        z = float(m.joints['wheel_%s_joint' % side].find('origin').get('xyz').split()[2])
        assert z - r == pytest.approx(0.0), 'wheel_%s does not touch z = 0' % side
    cz = float(m.joints['caster_joint'].find('origin').get('xyz').split()[2])
    assert cz - float(m.links['caster'].find('collision/geometry/sphere').get('radius')) == pytest.approx(0.0)
    plugins = [p.get('filename') for g in m.gazebo for p in g.iter('plugin')]
    assert plugins == ['libgazebo_ros_diff_drive.so'], plugins
    for n in m.links:
        assert mc.inertia_matrix(m.links[n].find('inertial')) == pytest.approx(
            mc.inertia_matrix(pw3.links[n].find('inertial')), rel=1e-6), n
