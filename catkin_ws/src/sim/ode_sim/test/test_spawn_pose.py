"""Spawning on a real sim_node lands models where Gazebo's gazebo_ros_api_plugin puts them
(description/spawning.py): initial_pose composed with the model's own <pose> (an SDF <model>'s,
an <include>'s, a URDF's <robot><origin>), an include without <pose> at initial_pose (the
included file's own <pose> dropped), and `rosrun gazebo_ros spawn_model -sdf -database NAME`
with -x -y -Y ending as a model:// <include> in /gazebo/get_world_sdf; sim_node restarted on
that saved world has every model where it was. The world is paused (-u): nothing moves."""
import json
import math
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest

from course_testing import Proc

HERE = os.path.dirname(os.path.abspath(__file__))
CLIENT = os.path.join(HERE, 'spawn_pose_client.py')

WORLD = """<?xml version="1.0"?>
<sdf version="1.6"><world name="default">
  <include><uri>model://ground_plane</uri></include>
</world></sdf>
"""
POSED_BOX = ('<sdf version="1.6"><model name="posed_box"><pose>5 5 5 0 0 0</pose>'
             '<link name="link"><inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy>'
             '<izz>0.1</izz></inertia></inertial><collision name="c"><geometry><box><size>'
             '0.3 0.3 0.3</size></box></geometry></collision></link></model></sdf>')


def yaw_q(yaw):
    return [0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]


def same_pose(a, b, tol=1e-6):
    return (all(abs(x - y) <= tol for x, y in zip(a[:3], b[:3]))
            and abs(abs(sum(x * y for x, y in zip(a[3:], b[3:]))) - 1.0) <= tol)


@pytest.fixture
def env(roscore, tmp_path):
    d = tmp_path / 'models' / 'posed_box'
    d.mkdir(parents=True)
    (d / 'model.config').write_text('<model><name>posed box</name>'
                                    '<sdf version="1.6">model.sdf</sdf></model>')
    (d / 'model.sdf').write_text(POSED_BOX)
    (tmp_path / 'home').mkdir()
    subprocess.run(['rosparam', 'set', '/use_sim_time', 'true'], env=roscore.env, check=True,
                   timeout=120)
    return dict(roscore.env, GAZEBO_MODEL_PATH=str(tmp_path / 'models'),
                HOME=str(tmp_path / 'home'), GAZEBO_MODEL_DATABASE_URI='')


def client(env, node, what):
    res = subprocess.run(['/usr/bin/python3', CLIENT, what], env=env, capture_output=True,
                         text=True, timeout=300)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:] + node.output()[-3000:]
    return json.loads(res.stdout.strip().splitlines()[-1])


def spawn_model(env, *args):
    res = subprocess.run(['rosrun', 'gazebo_ros', 'spawn_model'] + list(args), env=env,
                         capture_output=True, text=True, timeout=300)
    return res.returncode, res.stdout + res.stderr


def test_spawn_poses_includes_and_database(env, tmp_path):
    world = tmp_path / 'start.world'
    world.write_text(WORLD)
    node = Proc(['rosrun', 'ode_sim', 'sim_node', str(world), '-u'], env=env,
                log=str(tmp_path / 'sim1.log'))
    try:
        rc, out = spawn_model(env, '-sdf', '-database', 'posed_box', '-model', 'crate',
                              '-x', '1', '-y', '2', '-Y', '0.5')
        assert rc == 0, out
        rc, ghost = spawn_model(env, '-sdf', '-database', 'no_such_model', '-model', 'ghost')
        got = client(env, node, 'spawn')
    finally:
        node.stop()
    # a model found nowhere: the simulator's one line, then spawn_model's, exit 1
    assert rc == 1, ghost
    assert 'model://no_such_model: not found in GAZEBO_MODEL_PATH' in ghost, ghost
    assert 'Spawn service failed. Exiting.' in ghost and 'Traceback' not in ghost, ghost
    for key in ('posed', 'include_posed', 'include_bare', 'robot'):
        assert got[key][0], (key, got[key])
    m = got['models']
    assert set(m) == {'ground_plane', 'crate', 'posed', 'inc_posed', 'inc_bare', 'bot'}
    # initial (2, 3, 0, yaw 90 deg) + own <pose> (1, 0, 0.5, yaw 0.3): 1 m along the initial
    # pose's x axis, i.e. world +y
    assert same_pose(m['posed'], [2, 4, 0.5] + yaw_q(math.pi / 2 + 0.3)), m['posed']
    # include <pose> (0, 1, 0) after initial (3, 0, 0, yaw 90 deg): world -x
    assert same_pose(m['inc_posed'], [2, 0, 0] + yaw_q(math.pi / 2)), m['inc_posed']
    # an include without <pose>: initial_pose, the file's own <pose> (5 5 5) dropped
    assert same_pose(m['inc_bare'], [-1, -2, 0] + yaw_q(0.2)), m['inc_bare']
    # spawn_model -database with -x -y -Y
    assert same_pose(m['crate'], [1, 2, 0] + yaw_q(0.5)), m['crate']
    # URDF <robot><origin xyz="0 0 1"> after initial (1, 0, 0)
    assert same_pose(m['bot'], [1, 0, 1] + yaw_q(0)), m['bot']

    # Save World: includes stay includes at their current pose, the models are models
    w = ET.fromstring(got['sdf']).find('world')
    incs = {i.findtext('name'): i for i in w.findall('include')}
    assert set(incs) == {'ground_plane', 'crate', 'inc_posed', 'inc_bare'}
    crate = incs['crate']
    assert crate.findtext('uri') == 'model://posed_box'
    assert [float(v) for v in crate.findtext('pose').split()] == pytest.approx(
        [1, 2, 0, 0, 0, 0.5], abs=1e-9)
    assert incs['inc_posed'].findtext('uri') == 'model://posed_box'
    assert {e.get('name') for e in w.findall('model')} == {'posed', 'bot'}

    saved = tmp_path / 'saved.world'
    saved.write_text(got['sdf'])
    node = Proc(['rosrun', 'ode_sim', 'sim_node', str(saved), '-u'], env=env,
                log=str(tmp_path / 'sim2.log'))
    try:
        again = client(env, node, 'state')
    finally:
        node.stop()
    assert set(again['models']) == set(m)
    for name, p in m.items():
        assert same_pose(again['models'][name], p), (name, again['models'][name], p)
