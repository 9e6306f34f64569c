"""ode_sim.description.urdf_tree: a URDF's links and joints as plain data (no lumping), every
tree problem at once, one line each (no roscore)."""
import os

import pytest

from ode_sim.description import urdf_tree
from ode_sim.description.urdf_tree import NotUrdf, floats, number, parse_robot, read_tree, read_urdf

HERE = os.path.dirname(os.path.abspath(__file__))
FIX = os.path.join(HERE, 'fixtures', 'loaders')
SRC = os.path.abspath(os.path.join(HERE, '..', '..', '..'))     # catkin_ws/src

INERTIAL = ('<inertial><origin xyz="0 0 0.1"/><mass value="%s"/>'
            '<inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial>')


def link(name, body='', mass='1'):
    return '<link name="%s">%s%s</link>' % (name, body, INERTIAL % mass)


def joint(name, jtype, parent, child, body=''):
    return ('<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>%s</joint>'
            % (name, jtype, parent, child, body))


def robot(*parts):
    return '<robot name="r"><material name="red"><color rgba="1 0 0 1"/></material>%s</robot>' \
        % ''.join(parts)


ARM = robot(
    link('base', '<visual><origin rpy="0 0 1.5"/><geometry><box size="0.2 0.1 0.05"/></geometry>'
                 '<material name="red"/></visual>'
                 '<collision name="hull"><origin xyz="0 0 0.025"/><geometry><box size="0.2 0.1 0.05"/>'
                 '</geometry></collision>'),
    link('mount'), joint('mount_j', 'fixed', 'base', 'mount', '<origin xyz="0.1 0 0.05"/>'),
    link('upper', '<collision><geometry><cylinder radius="0.02" length="0.3"/></geometry></collision>'),
    joint('shoulder', 'revolute', 'mount', 'upper',
          '<origin xyz="0 0 0.1" rpy="0 0.5 0"/><axis xyz="0 1 0"/>'
          '<limit lower="-1.5" upper="1.5" effort="10" velocity="2"/><dynamics damping="0.1"/>'),
    link('finger', '<visual><geometry><mesh filename="package://p/f.stl" scale="1 1 1"/></geometry></visual>'),
    joint('slide', 'prismatic', 'upper', 'finger', '<axis xyz="1 0 0"/><limit effort="1" velocity="1"/>'
                                                   '<mimic joint="shoulder"/>'))


def test_links_and_joints_as_written():
    t = read_urdf(ARM)
    assert t.name == 'r' and t.problems == [] and t.roots() == ['base']
    assert list(t.links) == ['base', 'mount', 'upper', 'finger']
    assert list(t.joints) == ['mount_j', 'shoulder', 'slide']
    # the fixed joint is not lumped: mount stays a link of its own
    assert t.links['mount'].parent_joint == 'mount_j' and t.links['base'].child_joints == ['mount_j']
    sh = t.joints['shoulder']
    assert (sh.type, sh.parent, sh.child) == ('revolute', 'mount', 'upper')
    assert sh.origin.xyz == [0, 0, 0.1] and sh.origin.rpy == [0, 0.5, 0] and sh.axis == [0, 1, 0]
    assert sh.limit == {'lower': -1.5, 'upper': 1.5, 'effort': 10, 'velocity': 2}
    assert sh.dynamics_el.get('damping') == '0.1' and sh.mimic_el is None
    sl = t.joints['slide']
    assert sl.limit['lower'] is None and sl.mimic_el.get('joint') == 'shoulder'
    assert t.joints['mount_j'].axis is None and t.joints['mount_j'].limit is None
    base = t.links['base']
    [col], [vis] = base.collisions, base.visuals
    assert (col.name, col.kind, col.values, col.origin.xyz, col.origin.rpy) == \
        ('hull', 'box', {'size': [0.2, 0.1, 0.05]}, [0, 0, 0.025], [0, 0, 0])
    assert vis.origin.rpy == [0, 0, 1.5] and vis.material.name == 'red' and vis.material.rgba is None
    assert t.materials['red'].rgba == [1, 0, 0, 1]
    assert t.links['upper'].collisions[0].values == {'radius': [0.02], 'length': [0.3]}
    mesh = t.links['finger'].visuals[0]
    assert mesh.kind == 'mesh' and mesh.attrs['filename'] == 'package://p/f.stl' and mesh.values == {}
    ine = base.inertial
    assert ine.mass == 1 and ine.origin.xyz == [0, 0, 0.1]
    assert ine.inertia == {'ixx': 1, 'ixy': 0, 'ixz': 0, 'iyy': 2, 'iyz': 0, 'izz': 3}


def test_numbers_that_cannot_be_read_are_none_and_reading_goes_on():
    t = read_urdf(robot(
        link('a', '<collision><origin xyz="1 2" rpy=""/><geometry><box size="1 x 1"/></geometry></collision>',
             mass='heavy'),
        link('b'), joint('j', 'continuous', 'a', 'b', '<axis xyz="0 0"/><limit lower="-" upper="1"/>')))
    col = t.links['a'].collisions[0]
    assert col.origin.xyz is None and col.origin.rpy == [0, 0, 0]
    assert col.values['size'] is None and col.attrs['size'] == '1 x 1'
    assert t.links['a'].inertial.mass is None and t.links['a'].inertial.mass_el.get('value') == 'heavy'
    j = t.joints['j']
    assert j.axis is None and j.axis_el.get('xyz') == '0 0' and j.limit['lower'] is None
    assert j.limit['upper'] == 1
    assert t.problems == []       # values are the readers' business, not the tree's


def test_every_tree_problem_at_once():
    t = read_urdf(robot(
        link('a'), link('b'), link('c'), link('a'), link('lone'),
        '<joint name="nochild" type="fixed"><parent link="a"/></joint>',
        joint('j1', 'fixed', 'a', 'b'), joint('j2', 'fixed', 'c', 'b'),
        joint('ghost_j', 'revolute', 'a', 'ghost'), joint('odd', 'screw', 'b', 'c'),
        joint('j1', 'fixed', 'a', 'c')))
    assert t.problems == [
        'joint nochild: needs <parent link> and <child link>',
        'link b: child of two joints (j1, j2)',
        "joint ghost_j: child link 'ghost' is not defined",
        "joint odd: unknown type 'screw'",
        'two links named a',
        'two joints named j1',
        'the links form 2 trees (roots a, lone), expected one',
    ]
    assert [p for j in t.joints.values() for p in j.problems] == t.problems[:4]
    assert t.roots() == ['a', 'lone'] and t.links['b'].parent_joint == 'j1'
    assert not t.joints['nochild'].connects and t.joints['nochild'].parent == 'a'


def test_a_loop_and_no_root():
    t = read_urdf(robot(link('a'), link('b'), joint('ab', 'fixed', 'a', 'b'), joint('ba', 'fixed', 'b', 'a')))
    assert t.roots() == [] and t.loop == ['a', 'b']
    assert t.problems == ['the links form 0 trees (roots ), expected one',
                          'the joints form a loop through link a (joint ba)']
    t = read_tree(parse_robot(open(os.path.join(FIX, 'bad', 'loop.urdf')).read()))
    assert t.roots() == ['root'] and t.loop == ['a', 'b']
    assert t.problems == ['the joints form a loop through link a (joint j2)']


def test_not_a_urdf():
    with pytest.raises(NotUrdf) as e:
        parse_robot('<robot>')
    assert e.value.kind == 'xml' and str(e.value).startswith('not XML: no element found')
    with pytest.raises(NotUrdf) as e:
        read_urdf(b'<sdf version="1.6"/>')
    assert (e.value.kind, e.value.detail, str(e.value)) == ('root', 'sdf', 'the root element is <sdf>, not <robot>')


def test_number_parsing():
    assert floats('1 2e-3 -3') == [1, 0.002, -3] and floats('1 2', 3) is None
    assert floats(None) is None and floats('') is None and floats('1 a') is None
    assert number(' 4 ') == 4 and number('1 2') is None and number(None) is None
    assert urdf_tree.MOVING == ('revolute', 'continuous', 'prismatic')


@pytest.mark.parametrize('path', [os.path.join(FIX, 'urdf', n) for n in sorted(os.listdir(os.path.join(FIX, 'urdf')))]
                         + [os.path.join(SRC, 'course', 'my_robot_model', 'urdf', 'my_first_model.urdf')])
def test_good_urdf_files_are_one_tree(path):
    with open(path, 'rb') as f:
        t = read_urdf(f.read())
    assert t.problems == [] and len(t.roots()) == 1 and t.loop == []
    assert len(t.joints) == len(t.links) - 1
    assert all(j.parent in t.links and j.child in t.links for j in t.joints.values())
