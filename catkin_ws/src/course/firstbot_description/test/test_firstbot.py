"""firstbot_description: the tutorial's first robot (U 6.2-6.4) as printed — the URDF passes
check_urdf and urdf_to_graphviz, the xacro version expands to the same robot, and
display_robot.launch (model given as `model`) shows it in RViz under Xvfb with its TF."""
import os
import subprocess

import pytest

from course_testing import Proc, wait_for
from my_robot_model import model_check as mc

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
URDF = os.path.join(PKG, 'urdf', 'firstbot.urdf')
XACRO = os.path.join(PKG, 'urdf', 'first_robot.xacro')


def urdf_text():
    with open(URDF) as f:
        return f.read()


def floats(s):
    return [float(v) for v in s.split()]


def test_urdf_as_the_tutorial_prints_it():
    rc, out = mc.check_urdf(urdf_text())
    assert rc == 0, out
    assert 'root Link: base_link has 1 child(ren)' in out and 'child(1):  imu_link' in out, out
    m = mc.parse(urdf_text())
    base = m.links['base_link'].find('visual/geometry/cylinder')
    assert (float(base.get('radius')), float(base.get('length'))) == (0.10, 0.12)
    assert floats(m.links['imu_link'].find('visual/geometry/box').get('size')) == [0.02] * 3
    j = m.joints['imu_joint']
    assert j.get('type') == 'fixed' and j.find('parent').get('link') == 'base_link'
    assert floats(j.find('origin').get('xyz')) == [0.0, 0.0, 0.03]
    colours = mc.material_colours(urdf_text())
    assert colours['white'] == (1.0, 1.0, 1.0, 0.5) and colours['black'] == (0.0, 0.0, 0.0, 0.5)


def test_urdf_to_graphviz(tmp_path):
    out = subprocess.run(['urdf_to_graphviz', URDF], cwd=str(tmp_path), capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stdout + out.stderr
    gv = [f for f in os.listdir(str(tmp_path)) if f.endswith('.gv')]
    assert gv, os.listdir(str(tmp_path))
    with open(os.path.join(str(tmp_path), gv[0])) as f:
        graph = f.read()
    assert '"base_link"' in graph and '"imu_link"' in graph and '"imu_joint"' in graph, graph


def test_xacro_expands_to_the_same_robot():
    a, b = mc.parse(urdf_text()), mc.parse(mc.expand_xacro(XACRO))
    assert a.name == b.name == 'first_robot'
    assert sorted(a.links) == sorted(b.links) == ['base_link', 'imu_link']
    assert sorted(a.joints) == sorted(b.joints) == ['imu_joint']
    for n in a.links:
        ga, gb = a.links[n].find('visual/geometry')[0], b.links[n].find('visual/geometry')[0]
        assert ga.tag == gb.tag and {k: floats(v) for k, v in ga.attrib.items()} == \
            {k: floats(v) for k, v in gb.attrib.items()}, n
    assert floats(a.joints['imu_joint'].find('origin').get('xyz')) == \
        floats(b.joints['imu_joint'].find('origin').get('xyz'))
    assert mc.material_colours(urdf_text()) == mc.material_colours(mc.expand_xacro(XACRO))


@pytest.mark.parametrize('launch, args', [('display_robot.launch', []),
                                          ('display_robot.launch', ['model:=' + XACRO]),
                                          ('display_firstbot.launch', [])])
def test_display_launch_in_rviz(rviz_env, tmp_path, launch, args):
    env = dict(rviz_env)
    p = Proc(['roslaunch', 'firstbot_description', launch] + args, env=env, log=str(tmp_path / 'launch.log'))
    try:
        out = subprocess.run(['rostopic', 'echo', '-n', '1', '/tf_static'], env=env, capture_output=True,
                             text=True, timeout=120)
        assert out.returncode == 0 and 'child_frame_id: "imu_link"' in out.stdout, out.stdout + p.output()[-2000:]
        assert 'z: 0.03' in out.stdout, out.stdout
        desc = subprocess.run(['rosparam', 'get', '/robot_description'], env=env, capture_output=True,
                              text=True, timeout=60).stdout
        assert 'first_robot' in desc and 'imu_joint' in desc, desc
        # RViz is up once its node registers with the master
        wait_for(lambda: '/rviz' in subprocess.run(['rosnode', 'list'], env=env, capture_output=True,
                                                   text=True, timeout=60).stdout.split(),
                 120, 0.5, 'RViz to register with the master')
        assert p.alive() and 'process has died' not in p.output(), p.output()[-3000:]
    finally:
        p.stop()


@pytest.mark.parametrize('launch', ['display_robot.launch', 'display_firstbot.launch'])
def test_model_path_as_the_tutorial_types_it(rviz_env, tmp_path, launch):
    """U 6.4 gives the model file as `model_path:=`; both launch files load that file."""
    other = tmp_path / 'renamed.urdf'
    other.write_text(urdf_text().replace('name="first_robot"', 'name="model_path_robot"'))
    env = dict(rviz_env)
    p = Proc(['roslaunch', 'firstbot_description', launch, 'model_path:=' + str(other), 'rviz:=false'],
             env=env, log=str(tmp_path / 'launch.log'))
    try:
        out = subprocess.run(['rostopic', 'echo', '-n', '1', '/tf_static'], env=env, capture_output=True,
                             text=True, timeout=120)
        assert out.returncode == 0 and 'child_frame_id: "imu_link"' in out.stdout, out.stdout + p.output()[-2000:]
        desc = subprocess.run(['rosparam', 'get', '/robot_description'], env=env, capture_output=True,
                              text=True, timeout=60).stdout
        assert 'model_path_robot' in desc, desc
    finally:
        p.stop()
