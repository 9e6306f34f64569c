"""Unit tests of lab 3's model analysis and report logic (no roscore, no build)."""
import os
import re

import pytest

from grading import package
from grading.lab3 import model, rules, rviz
from grading.labs import load_variants
from grading.urdf import ModelError, body_size, parse_urdf, root_link

HERE = os.path.dirname(os.path.abspath(__file__))


def link(name, shape='box', dims='0.1 0.1 0.1', mass='0.1', rpy='0 0 0', inertial=True, visual=True):
    geo = {'box': '<box size="%s"/>' % dims, 'cylinder': '<cylinder radius="0.03" length="0.02"/>',
           'sphere': '<sphere radius="0.02"/>'}
    col = ('<collision><origin xyz="0 0 0" rpy="%s"/><geometry>%s</geometry></collision>' % (rpy, geo[shape])
           if shape else '')
    vis = '<visual><geometry>%s</geometry></visual>' % geo[shape or 'box'] if visual else ''
    ine = ('<inertial><mass value="%s"/>'
           '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>' % mass
           if inertial else '')
    return '<link name="%s">%s%s%s</link>' % (name, vis, col, ine)


def joint(name, typ, parent, child, mimic=False):
    return ('<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>%s'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
            % (name, typ, parent, child, '<mimic joint="a1"/>' if mimic else ''))


def robot(*parts):
    return '<robot name="r">%s</robot>' % ''.join(parts)


def base(**kw):
    return [link('base_link', dims='0.2 0.14 0.09', **kw),
            link('wl', 'cylinder'), joint('wl_j', 'continuous', 'base_link', 'wl'),
            link('wr', 'cylinder'), joint('wr_j', 'continuous', 'base_link', 'wr')]


def test_variant_table():
    v = load_variants('lab3')
    assert sorted(v) == list(range(10))
    assert [v[d]['links'] for d in range(10)] == [10, 5, 6, 7, 8, 5, 6, 7, 8, 9]
    assert v[4]['wheels'] == 'CCS' and v[9]['arm'] == 'RPRC' and v[0]['body'] == [200, 180, 120]
    for d in range(10):   # every variant is buildable: links >= body + one link per arm joint
        assert v[d]['links'] >= 1 + len(v[d]['arm'])


def test_reference_xacro_carries_the_same_table():
    with open(os.path.join(HERE, 'reference/my_firts_robot_model/urdf/my_robots_super_model.xacro')) as f:
        text = f.read()
    rows = re.findall(r"dict\(links=(\d+),\s*arm='(\w+)',\s*wheels='(\w+)',\s*body=\[([\d., ]+)\]\)", text)
    v = load_variants('lab3')
    assert [(int(l), a, w, [round(float(x) * 1000) for x in b.split(',')]) for l, a, w, b in rows] == \
        [(v[d]['links'], v[d]['arm'], v[d]['wheels'], v[d]['body']) for d in range(10)]


def test_analyse_wheels_arm_links():
    m = parse_urdf(robot(*base(), link('mount'), joint('mount_j', 'fixed', 'base_link', 'mount'),
                         link('a1'), joint('j1', 'revolute', 'mount', 'a1'),
                         link('a2', 'cylinder'), joint('j2', 'prismatic', 'a1', 'a2'),
                         link('a3'), joint('j3', 'continuous', 'a2', 'a3'),
                         link('ball', 'sphere'), joint('ball_j', 'fixed', 'base_link', 'ball'),
                         link('cam'), joint('cam_j', 'fixed', 'base_link', 'cam')))
    a = model.analyse(m)
    assert a['arm'] == ['j1', 'j2', 'j3'] and a['arm_codes'] == 'RPC'
    assert sorted(a['wheels']) == [('ball_j', 'S'), ('wl_j', 'C'), ('wr_j', 'C')]
    assert a['links'] == ['a1', 'a2', 'a3', 'base_link', 'cam', 'mount']
    assert [round(x) for x in body_size(m, 'base_link')] == [200, 140, 90]


def test_branching_arm_and_mimic():
    m = parse_urdf(robot(*base(), link('a1'), joint('a1', 'revolute', 'base_link', 'a1'),
                         link('f1'), joint('f1', 'prismatic', 'a1', 'f1'),
                         link('f2'), joint('f2', 'prismatic', 'a1', 'f2')))
    assert model.analyse(m)['branch'] == ('f1', 'f2')
    m = parse_urdf(robot(*base(), link('a1'), joint('a1', 'revolute', 'base_link', 'a1'),
                         link('f1'), joint('f1', 'prismatic', 'a1', 'f1'),
                         link('f2'), joint('f2', 'prismatic', 'a1', 'f2', mimic=True)))
    a = model.analyse(m)
    assert a['branch'] is None and a['arm_codes'] == 'RP'


def test_rotated_body_box_and_missing_box():
    m = parse_urdf(robot(link('base_link', dims='0.14 0.2 0.09', rpy='0 0 1.5707963')))
    assert [round(x) for x in body_size(m, 'base_link')] == [200, 140, 90]
    m = parse_urdf(robot(link('base_link', 'cylinder')))
    with pytest.raises(ModelError, match='base_link has no box collision'):
        body_size(m, 'base_link')


def test_link_problems():
    m = parse_urdf(robot(link('base_footprint', shape=None, visual=False, inertial=False),
                         joint('fp', 'fixed', 'base_footprint', 'base_link'),
                         link('base_link', mass='0'), link('w', shape=None),
                         joint('wj', 'continuous', 'base_link', 'w'),
                         link('x', inertial=False), joint('xj', 'fixed', 'base_link', 'x')))
    assert model.link_problems(m) == ['base_link: mass 0', 'w: no <collision>', 'x: no <inertial>']


def test_parse_errors_are_one_line():
    with pytest.raises(ModelError, match='not XML'):
        parse_urdf('<robot>')
    with pytest.raises(ModelError, match='2 trees'):
        root_link(parse_urdf(robot(link('a'), link('b'))))
    with pytest.raises(ModelError, match='box size'):
        parse_urdf(robot(link('a', dims='0.1 0.1')))
    with pytest.raises(ModelError, match=r"^the root element is <sdf>, not <robot>$"):
        parse_urdf('<sdf/>')
    with pytest.raises(ModelError, match=r"^link a collision cylinder radius: 'r' is not a number$"):
        parse_urdf(robot(link('a', 'cylinder').replace('radius="0.03"', 'radius="r"')))
    with pytest.raises(ModelError, match=r"^origin rpy: '0 0' is not 3 numbers$"):
        parse_urdf(robot(link('a', rpy='0 0')))
    with pytest.raises(ModelError, match=r'^link a: inertial values are not numbers$'):
        parse_urdf(robot(link('a', mass='heavy')))
    with pytest.raises(ModelError, match=r'^the model has no <link>$'):
        parse_urdf(robot())


def test_parse_urdf_view():
    m = parse_urdf(robot(link('a', rpy='0 0 1'), link('b', 'sphere', visual=False, inertial=False),
                         joint('j', 'revolute', 'a', 'b', mimic=True),
                         '<link name="c"><collision><geometry/></collision>'
                         '<inertial><inertia ixx="1" iyy="2"/></inertial></link>'))
    assert m['name'] == 'r' and list(m['links']) == ['a', 'b', 'c']
    assert m['links']['a'] == {'collisions': [('box', [0.1, 0.1, 0.1], (0.0, 0.0, 1.0))], 'visual': True,
                               'inertial': {'mass': 0.1, 'inertia': {'ixx': 1e-4, 'iyy': 1e-4, 'izz': 1e-4}}}
    assert m['links']['b'] == {'collisions': [('sphere', [0.02], (0.0, 0.0, 0.0))], 'visual': False,
                               'inertial': None}
    c = m['links']['c']
    assert c['collisions'] == [] and c['inertial']['mass'] is None
    assert c['inertial']['inertia']['iyy'] == 2 and c['inertial']['inertia']['izz'] != c['inertial']['inertia']['izz']
    assert m['joints'] == {'j': {'type': 'revolute', 'parent': 'a', 'child': 'b', 'mimic': True}}


def test_rviz_config_and_command_line():
    cfg = ('Visualization Manager:\n  Displays:\n    - Class: rviz/Grid\n    - Class: rviz/Group\n'
           '      Displays:\n        - Class: rviz/RobotModel\n    - Class: rviz/TF\n      Enabled: false\n'
           '  Global Options:\n    Fixed Frame: base_link\n')
    assert rviz.rviz_displays(cfg) == (['rviz/Grid', 'rviz/Group', 'rviz/RobotModel'], 'base_link')
    with pytest.raises(ModelError):
        rviz.rviz_displays('Panels: []\n')
    assert rviz.rviz_config_arg(['/usr/bin/rviz', '-d', '/x.rviz', '__name:=rviz']) == '/x.rviz'
    assert rviz.rviz_config_arg(['/usr/bin/rviz', '--display-config=/y.rviz']) == '/y.rviz'
    assert rviz.rviz_config_arg(['/usr/bin/rviz']) is None
    assert (rviz.node_kind(['/usr/bin/python3', '/usr/lib/joint_state_publisher_gui/joint_state_publisher_gui'])
            == 'joint_state_publisher')
    assert (rviz.node_kind(['/usr/lib/robot_state_publisher/robot_state_publisher', '__name:=x'])
            == 'robot_state_publisher')
    assert rviz.node_kind(['/usr/bin/python3', '/tmp/talker.py']) is None


def test_variant_args(tmp_path):
    p = tmp_path / 'm.xacro'
    p.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:arg name="variant" default="1"/></robot>')
    assert package.variant_args(model.xacro_args(str(p)), '123457') == ['variant:=7']
    p.write_text('<robot/>')
    assert package.variant_args(model.xacro_args(str(p)), '123457') == []


def obs_for(urdf, **launch):
    la = {'robot_description': urdf, 'kinds': {'robot_state_publisher': ['/rsp'], 'joint_state_publisher': ['/jsp'],
                                               'rviz': ['/rviz']},
          'rviz': {'config': '/c.rviz', 'classes': ['rviz/RobotModel', 'rviz/TF'], 'fixed_frame': 'base_link'},
          'tf_frames': sorted(parse_urdf(urdf)['links']), 'ready_after': 3.0}
    la.update(launch)
    return {'isu': '1231', 'model_found': True, 'urdf': urdf, 'xacro_args': [], 'launch': la}


V1 = robot(*base(), link('a1'), joint('j1', 'revolute', 'base_link', 'a1'),
           link('a2'), joint('j2', 'revolute', 'a1', 'a2'),
           link('a3'), joint('j3', 'revolute', 'a2', 'a3'),
           link('a4'), joint('j4', 'revolute', 'a3', 'a4'))


def test_evaluate_variant_1():
    crits = rules.evaluate(obs_for(V1))
    assert [c.passed for c in crits] == [True] * 7, [c.reason['en'] for c in crits]
    no_tf = rules.evaluate(obs_for(V1, tf_frames=['base_link']))[6]
    assert not no_tf.passed and 'no TF for links: a1, a2, a3, a4, wl, wr' in no_tf.reason['en']
    no_cfg = rules.evaluate(obs_for(V1, rviz={'config': None}))[6]
    assert not no_cfg.passed and 'rviz runs without a config' in no_cfg.reason['en']
    no_tf_disp = rules.evaluate(obs_for(V1, rviz={'config': '/c.rviz', 'classes': ['rviz/RobotModel'],
                                                  'fixed_frame': 'map'}))[6]
    assert 'has no TF display' in no_tf_disp.reason['en'] and 'Fixed Frame "map"' in no_tf_disp.reason['en']
    other = rules.evaluate(obs_for(V1, robot_description=robot(*base())))[6]
    assert 'holds another model' in other.reason['en']
    bad = rules.evaluate({'isu': '1231', 'model_found': True, 'xacro_error': 'Undefined property x',
                         'launch': {'error': 'launch/lab3_setup.launch not found in package my_firts_robot_model'}})
    assert [c.passed for c in bad] == [False] * 7
    assert bad[0].reason['en'] == 'xacro: Undefined property x' and 'not checked' in bad[1].reason['en']


def test_links_pass_in_either_count():
    """Table 11.1's "Кол-во звеньев": every <link> (the book's count) or the links without wheels."""
    arm = [link('a1'), joint('j1', 'prismatic', 'base_link', 'a1'), link('a2'), joint('j2', 'revolute', 'a1', 'a2'),
           link('a3'), joint('j3', 'revolute', 'a2', 'a3')]
    obs = dict(obs_for(robot(*base(), *arm)), isu='1232')            # variant 2: 6 links, PRR, CC
    c2 = rules.evaluate(obs)[1]
    assert c2.passed and c2.reason['en'].startswith('6 links in the model (every <link>, as the book counts)'), \
        c2.reason
    helpers = [link('mount'), joint('m_j', 'fixed', 'base_link', 'mount'),
               link('grip'), joint('g_j', 'fixed', 'a3', 'grip')]
    obs = dict(obs_for(robot(*base(), *arm, *helpers)), isu='1232')  # 8 links, 6 without the wheels
    c2 = rules.evaluate(obs)[1]
    assert c2.passed and c2.reason['en'].startswith('6 links without wheels'), c2.reason
    obs = dict(obs_for(robot(*base(), *arm[:4])), isu='1232')         # 5 links, 3 without the wheels
    c2 = rules.evaluate(obs)[1]
    assert not c2.passed
    assert c2.reason['en'] == ('the model has 5 links (every <link>), 3 without wheels (a1, a2, base_link); '
                               'the variant wants 6 in either count')
