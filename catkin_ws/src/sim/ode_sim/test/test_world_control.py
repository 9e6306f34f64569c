"""The simulator's window API for real (issue 31): sim_node on a world, a client process that
inserts a model:// include, a box, a URDF robot and a light, moves one, deletes one, pauses and
steps 100 steps (sim time + 100 x step exactly), reads /gazebo/world_stats and /gazebo/pose_info
and saves the world
through /gazebo/get_world_sdf; sim_node restarted on the saved file has the same models at the
same poses (and the robot's joint where it was, its ros_control bridge serving it)."""
import json
import math
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest

from course_testing import Proc

HERE = os.path.dirname(os.path.abspath(__file__))
CLIENT = os.path.join(HERE, 'world_control_client.py')

WORLD = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="default">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
    <include><uri>model://traffic_cone</uri><name>cone_world</name><pose>-1 1 0 0 0 0</pose></include>
    <include><uri>model://traffic_cone</uri><name>cone_kept</name><pose>-2 -1 0 0 0 1</pose></include>
  </world>
</sdf>
"""


def sim(roscore, world, log, *args):
    subprocess.run(['rosparam', 'set', '/use_sim_time', 'true'], env=roscore.env, check=True,
                   timeout=120)
    return Proc(['rosrun', 'ode_sim', 'sim_node', world] + list(args), env=roscore.env,
                log=str(log))


def client(roscore, node, *args):
    res = subprocess.run(['/usr/bin/python3', CLIENT] + list(args), env=roscore.env,
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:] + node.output()[-3000:]
    return json.loads(res.stdout.strip().splitlines()[-1])


def same_pose(a, b, tol):
    """Positions within tol (m), orientations within tol (quaternion dot)."""
    return (all(abs(x - y) <= tol for x, y in zip(a[:3], b[:3]))
            and abs(abs(sum(x * y for x, y in zip(a[3:], b[3:]))) - 1.0) <= tol)


def test_insert_move_delete_step_save_and_reload(roscore, tmp_path):
    world = tmp_path / 'start.world'
    world.write_text(WORLD)
    saved = str(tmp_path / 'saved.world')
    node = sim(roscore, str(world), tmp_path / 'sim1.log')
    try:
        out = client(roscore, node, 'edit', saved)
    finally:
        node.stop()
    for key in ('spawn_include', 'spawn_box', 'spawn_urdf', 'spawn_light', 'spawn_walls', 'move',
                'config', 'delete'):
        assert out[key][0], (key, out[key])
    assert out['spawn_light_dup'] == [False, 'SpawnModel: Failure - entity already exists.']
    assert out['light_props'] == [True, pytest.approx(0.9)]
    ok, msg = out['step_running']
    assert not ok and 'pause' in msg, msg
    # exactly 100 steps of the world's step
    ok, msg, sim_time, iterations = out['step']
    assert ok, msg
    assert out['step_size'] == 0.001
    assert sim_time - out['t0'] == pytest.approx(100 * out['step_size'], abs=1e-9)
    assert out['t1'] == pytest.approx(sim_time, abs=1e-9)
    assert out['stats1']['iterations'] == iterations
    assert out['stats1']['iterations'] - out['stats0']['iterations'] == 100
    assert out['stats1']['paused'] and out['stats0']['paused']
    assert out['stats1']['sim_time'] == pytest.approx(sim_time, abs=1e-9)
    assert out['stats1']['max_step_size'] == 0.001 and out['stats1']['rtf'] == 0.0
    assert out['stats1']['pause_time'] > 0 and out['stats1']['real_time'] > 0
    # the saved file: includes stay includes, the box and the robot are models, the light
    assert out['sdf'][0], out['sdf']
    w = ET.parse(saved).getroot().find('world')
    incs = {i.findtext('name'): i.findtext('uri') for i in w.findall('include')}
    assert incs == {'ground_plane': 'model://ground_plane', 'cone_kept': 'model://traffic_cone',
                    'cone_a': 'model://traffic_cone'}
    assert {m.get('name') for m in w.findall('model')} == {'box_a', 'arm', 'walls_1'}
    walls = next(m for m in w.findall('model') if m.get('name') == 'walls_1')
    assert walls.findtext('static') == 'true' and len(walls.findall('link/collision')) == 2
    assert {l.get('name') for l in w.findall('light')} == {'sun', 'lamp_1'}
    before = out['state']
    assert set(before['models']) == {'ground_plane', 'cone_kept', 'cone_a', 'box_a', 'arm',
                                     'walls_1'}
    assert before['models']['box_a'][:2] == pytest.approx([3, 3], abs=0.01)
    assert before['joints']['shoulder'] == pytest.approx(0.6, abs=0.02)

    assert out['control_joints'] == ['shoulder']
    # restart on the saved file (paused, so nothing moves before we look); the arm's URDF on the
    # parameter server, as its launch file puts it: gazebo_ros_control reads the
    # transmissions from there (the saved SDF has none, as Gazebo's)
    urdf = subprocess.run(['/usr/bin/python3', CLIENT, 'arm_urdf'], env=roscore.env,
                          capture_output=True, text=True, timeout=120, check=True).stdout
    subprocess.run(['rosparam', 'set', '/arm/robot_description', urdf], env=roscore.env,
                   check=True, timeout=120)
    node = sim(roscore, saved, tmp_path / 'sim2.log', '-u')
    try:
        after = client(roscore, node, 'state')
    finally:
        node.stop()
    assert set(after['models']) == set(before['models'])
    for name, p in before['models'].items():
        assert same_pose(after['models'][name], p, 1e-6), (name, after['models'][name], p)
    for name, p in before['links'].items():
        assert same_pose(after['links'][name], p, 1e-6), (name, after['links'][name], p)
    assert after['joints']['shoulder'] == pytest.approx(before['joints']['shoulder'], abs=1e-6)
    assert after['lights'] == {'sun': True, 'lamp_1': True}
    for out_state in (before, after):           # /gazebo/pose_info agrees with the services
        info = out_state['pose_info']
        assert set(info['models']) == set(out_state['models'])
        for name, p in out_state['models'].items():
            assert same_pose(info['models'][name], p, 1e-6), name
        for name, p in out_state['links'].items():
            assert same_pose(info['links'][name], p, 1e-6), name
    assert after['control_joints'] == ['shoulder']
    assert math.isclose(after['sim_time'], 0.0, abs_tol=1e-9)
