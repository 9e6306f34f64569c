"""spawn_model without a ROS master: arguments, model XML sources and checks, pose."""
import io
import math
import random
import xml.etree.ElementTree as ET

import pytest

from gazebo_ros import spawn_model as sm

URDF = '<robot name="r"><link name="base_link"/></robot>'


def parse(*argv, ns='/'):
    return sm.parse_args(list(argv), ns)


def test_defaults():
    a = parse('-urdf', '-param', 'robot_description', '-model', 'bot')
    assert a.urdf and not a.sdf and a.param == 'robot_description' and a.model == 'bot'
    assert (a.x, a.y, a.z, a.R, a.P, a.Y) == (0, 0, 0, 0, 0, 0)
    assert a.gazebo_namespace == '/gazebo' and a.robot_namespace == '/'
    assert a.reference_frame == '' and a.joints == [] and a.wait is None
    assert not (a.unpause or a.bond or a.package_to_model)


def test_all_arguments():
    a = parse('-sdf', '-file', 'm.sdf', '-model', 'm', '-x', '1.5', '-y', '-2', '-z', '0.25',
              '-R', '0.1', '-P', '-0.2', '-Y', '3.1', '-J', 'j1', '0.5', '-J', 'j2', '-0.1',
              '-reference_frame', 'table::top', '-gazebo_namespace', '/sim',
              '-robot_namespace', '/robot1', '-unpause', '-wait', 'table',
              '-package_to_model', '-b', ns='/ns/')
    assert a.sdf and a.file == 'm.sdf'
    assert (a.x, a.y, a.z, a.R, a.P, a.Y) == (1.5, -2.0, 0.25, 0.1, -0.2, 3.1)
    assert a.joints == [('j1', 0.5), ('j2', -0.1)]
    assert a.reference_frame == 'table::top' and a.gazebo_namespace == '/sim'
    assert a.robot_namespace == '/robot1' and a.wait == 'table'
    assert a.unpause and a.package_to_model and a.bond


def test_robot_namespace_default_is_the_nodes():
    assert parse('-urdf', '-stdin', '-model', 'm', ns='/robot2/').robot_namespace == '/robot2/'


@pytest.mark.parametrize('argv', [
    ['-file', 'a', '-model', 'm'],                              # no format
    ['-urdf', '-sdf', '-file', 'a', '-model', 'm'],             # two formats
    ['-urdf', '-model', 'm'],                                   # no source
    ['-urdf', '-file', 'a', '-stdin', '-model', 'm'],           # two sources
    ['-urdf', '-file', 'a'],                                    # no -model
    ['-urdf', '-file', 'a', '-model', 'm', '-x', 'one'],        # not a number
    ['-urdf', '-file', 'a', '-model', 'm', '-J', 'j1'],         # -J needs two values
    ['-urdf', '-file', 'a', '-model', 'm', '-J', 'j1', 'up'],   # joint position not a number
])
def test_bad_arguments_exit_2_with_one_message(argv, capsys):
    with pytest.raises(SystemExit) as e:
        parse(*argv)
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert 'spawn_model: error:' in err and 'Traceback' not in err


def test_bad_joint_position_names_the_joint(capsys):
    with pytest.raises(SystemExit):
        parse('-urdf', '-file', 'a', '-model', 'm', '-J', 'left_wheel', 'up')
    assert '-J left_wheel up: the joint position is not a number' in capsys.readouterr().err


# ------------------------------------------------------------------------------------ sources

def test_file_source(tmp_path):
    f = tmp_path / 'r.urdf'
    f.write_text(URDF)
    assert sm.load_model_xml(parse('-urdf', '-file', str(f), '-model', 'r')) == URDF


@pytest.mark.parametrize('make,msg', [
    (lambda p: str(p / 'missing.urdf'), 'does not exist'),
    (lambda p: str(p), 'is not a file'),
    (lambda p: (p / 'e.urdf').write_text('  \n') and str(p / 'e.urdf'), 'is empty'),
])
def test_bad_file(tmp_path, make, msg):
    path = make(tmp_path)
    with pytest.raises(sm.SpawnError) as e:
        sm.load_model_xml(parse('-urdf', '-file', path, '-model', 'r'))
    assert msg in str(e.value) and path in str(e.value)


def test_param_source():
    params = {'/robot_description': URDF, '/empty': ''}
    a = parse('-urdf', '-param', '/robot_description', '-model', 'r')
    assert sm.load_model_xml(a, get_param=params.get) == URDF
    for name in ('/empty', '/missing'):
        with pytest.raises(sm.SpawnError, match='param %s does not exist or is empty' % name):
            sm.load_model_xml(parse('-urdf', '-param', name, '-model', 'r'),
                              get_param=params.get)


def test_stdin_source():
    a = parse('-urdf', '-stdin', '-model', 'r')
    assert sm.load_model_xml(a, stdin=io.StringIO(URDF)) == URDF
    with pytest.raises(sm.SpawnError, match='stdin buffer was empty'):
        sm.load_model_xml(a, stdin=io.StringIO(''))


def test_database_sends_the_originals_include():
    """-database MODEL sends gazebo_ros' template, <sdf><world><include><uri>model://MODEL:
    the simulator finds the model (as gzserver) and keeps it an include; nothing is looked up
    here, so a model only the simulator's machine has spawns too."""
    text = sm.load_model_xml(parse('-sdf', '-database', 'traffic_cone', '-model', 'm'))
    assert text == sm.database_include('traffic_cone')
    root = ET.fromstring(text)
    assert root.tag == 'sdf' and root.get('version') == '1.4'
    world = root.find('world')
    assert world.get('name') == 'default' and [c.tag for c in world] == ['include']
    inc = world.find('include')
    assert [c.tag for c in inc] == ['uri'] and inc.findtext('uri') == 'model://traffic_cone'
    assert sm.process_xml(text) == text         # sent as it is
    assert 'model://no_such_model' in sm.load_model_xml(
        parse('-sdf', '-database', 'no_such_model', '-model', 'x'))


# --------------------------------------------------------------------------------------- XML

def test_invalid_xml():
    with pytest.raises(sm.SpawnError) as e:
        sm.process_xml('<robot name="r"><link></robot>')
    assert str(e.value).startswith('Invalid XML: mismatched tag: line 1')


def test_valid_xml_is_sent_unchanged():
    text = ('<?xml version="1.0"?>\n<!-- comment -->\n<robot xmlns:xacro="http://ros.org/wiki/'
            'xacro" name="r"><link name="b"/></robot>')
    assert sm.process_xml(text) == text
    assert sm.process_xml(text, rewrite_package_uris=True) == text   # nothing to rewrite


def test_package_to_model():
    text = ('<robot name="r"><link name="b"><visual><geometry>'
            '<mesh filename="package://my_robot/meshes/base.stl" scale="1 1 1"/>'
            '</geometry></visual><collision><geometry>'
            '<mesh filename="file:///abs/wheel.stl"/></geometry></collision></link></robot>')
    out = sm.process_xml(text, rewrite_package_uris=True)
    assert 'filename="model://my_robot/meshes/base.stl"' in out
    assert 'filename="file:///abs/wheel.stl"' in out and 'package://' not in out
    assert sm.process_xml(text) == text


# -------------------------------------------------------------------------------------- pose

def tf_quaternion(r, p, y):
    """Reference: product of the axis rotations qz(y) * qy(p) * qx(r) (static x, y, z)."""
    def mul(a, b):
        ax, ay, az, aw = a
        bx, by, bz, bw = b
        return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
                aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)
    qx = (math.sin(r / 2), 0, 0, math.cos(r / 2))
    qy = (0, math.sin(p / 2), 0, math.cos(p / 2))
    qz = (0, 0, math.sin(y / 2), math.cos(y / 2))
    return mul(qz, mul(qy, qx))


def test_quaternion_matches_sxyz():
    rnd = random.Random(4)
    for _ in range(50):
        rpy = [rnd.uniform(-math.pi, math.pi) for _ in range(3)]
        assert sm.quaternion_from_euler(*rpy) == pytest.approx(tf_quaternion(*rpy), abs=1e-12)
    assert sm.quaternion_from_euler(0, 0, math.pi / 2) == pytest.approx(
        (0, 0, math.sqrt(0.5), math.sqrt(0.5)))


def test_quaternion_matches_tf_transformations():
    import tf.transformations as tft   # Debian's python3-tf: missing = broken install
    for rpy in ((0.1, 0.2, 0.3), (-1.0, 0.5, 2.5), (3.0, -1.2, -0.7)):
        assert sm.quaternion_from_euler(*rpy) == pytest.approx(
            tuple(tft.quaternion_from_euler(*rpy)), abs=1e-12)


def test_initial_pose():
    p = sm.initial_pose(parse('-urdf', '-stdin', '-model', 'm', '-x', '1', '-y', '2', '-z', '3',
                              '-Y', str(math.pi)))
    assert (p.position.x, p.position.y, p.position.z) == (1, 2, 3)
    assert (p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w) == pytest.approx(
        (0, 0, 1, 0), abs=1e-12)
