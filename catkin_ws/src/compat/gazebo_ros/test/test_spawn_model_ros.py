"""spawn_model end to end: `rosrun gazebo_ros spawn_model ...` against a fake simulator
(test/fake_gazebo.py) on a private roscore; the fake records every request it gets."""
import json
import math
import os
import signal
import subprocess
import sys
import time

import pytest

from course_testing import Proc, RosCore, stop_tree, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
URDF = ('<?xml version="1.0"?>\n<robot name="cart"><link name="base_link"/>'
        '<link name="wheel"><visual><geometry><mesh filename="package://cart/meshes/w.stl"/>'
        '</geometry></visual></link>'
        '<joint name="axle" type="continuous"><parent link="base_link"/><child link="wheel"/>'
        '</joint></robot>')


class Sim:
    """A roscore plus the fake simulator serving /gazebo and /sim2."""

    def __init__(self, tmp):
        self.core = RosCore(log_dir=str(tmp / 'ros_log')).start()
        self.env = dict(self.core.env)
        self.env.pop('ROS_NAMESPACE', None)
        self.record = str(tmp / 'requests.jsonl')
        self.fake = Proc([sys.executable, os.path.join(HERE, 'fake_gazebo.py'), self.record,
                          '/gazebo', '/sim2'], env=self.env, log=str(tmp / 'fake.log'))
        wait_for(lambda: self.requests(service='ready'), 30, what='the fake simulator')

    def requests(self, **match):
        if not os.path.exists(self.record):
            return []
        with open(self.record) as f:
            rows = [json.loads(line) for line in f if line.endswith('\n')]
        return [r for r in rows if all(r.get(k) == v for k, v in match.items())]

    def stop(self):
        self.fake.stop()
        self.core.stop()


@pytest.fixture(scope='module')
def sim(tmp_path_factory):
    s = Sim(tmp_path_factory.mktemp('spawn_model'))
    try:
        yield s
    finally:
        s.stop()


def spawn(sim, *args, stdin=None, env=None, timeout=40):
    """Run spawn_model to the end; (exit code, output)."""
    p = subprocess.Popen(['rosrun', 'gazebo_ros', 'spawn_model'] + list(args),
                         env=env or sim.env, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        out, _ = p.communicate(stdin or '', timeout=timeout)
    except subprocess.TimeoutExpired:
        stop_tree(p)
        out, _ = p.communicate()
        raise AssertionError('spawn_model %s did not finish in %d s:\n%s' % (args, timeout, out))
    return p.returncode, out


def test_param_with_pose_joints_and_unpause(sim):
    import rosgraph
    rosgraph.Master('/test', master_uri=sim.core.uri).setParam('/robot_description', URDF)
    rc, out = spawn(sim, '-urdf', '-param', 'robot_description', '-model', 'cart1',
                    '-x', '1.5', '-y', '-2', '-z', '0.1', '-R', '0.1', '-P', '0.2', '-Y', '0.3',
                    '-J', 'axle', '0.75', '-J', 'other', '-1.5', '-unpause',
                    '-reference_frame', 'world')
    assert rc == 0, out
    [req] = sim.requests(service='/gazebo/spawn_urdf_model', model_name='cart1')
    assert req['model_xml'] == URDF and req['robot_namespace'] == '/'
    assert req['reference_frame'] == 'world'
    cr, sr = math.cos(0.05), math.sin(0.05)
    cp, sp = math.cos(0.1), math.sin(0.1)
    cy, sy = math.cos(0.15), math.sin(0.15)
    q = [sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
         cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy]
    assert req['pose'] == pytest.approx([1.5, -2, 0.1] + q, abs=1e-12)
    [conf] = sim.requests(service='/gazebo/set_model_configuration', model_name='cart1')
    assert conf['joint_names'] == ['axle', 'other']
    assert conf['joint_positions'] == [0.75, -1.5] and conf['urdf_param_name'] == ''
    assert sim.requests(service='/gazebo/unpause_physics')
    assert 'Spawn status: fake: spawned cart1' in out


def test_file_sdf_custom_namespaces_and_package_to_model(sim, tmp_path):
    f = tmp_path / 'cart.urdf'
    f.write_text(URDF)
    env = dict(sim.env, ROS_NAMESPACE='/robot1')
    rc, out = spawn(sim, '-sdf', '-file', str(f), '-model', 'cart2', '-gazebo_namespace', '/sim2',
                    '-package_to_model', env=env)
    assert rc == 0, out
    [req] = sim.requests(service='/sim2/spawn_sdf_model', model_name='cart2')
    assert req['robot_namespace'] == '/robot1/'          # default: the node's namespace
    assert 'model://cart/meshes/w.stl' in req['model_xml'] and 'package://' not in req['model_xml']
    assert req['pose'] == [0, 0, 0, 0, 0, 0, 1]
    assert not sim.requests(model_name='cart2', service='/gazebo/spawn_sdf_model')
    rc, out = spawn(sim, '-sdf', '-file', str(f), '-model', 'cart3', '-robot_namespace', '/r3')
    assert rc == 0, out
    assert sim.requests(service='/gazebo/spawn_sdf_model', model_name='cart3')[0][
        'robot_namespace'] == '/r3'


def test_stdin(sim):
    rc, out = spawn(sim, '-urdf', '-stdin', '-model', 'cart4', stdin=URDF)
    assert rc == 0, out
    assert sim.requests(model_name='cart4')[0]['model_xml'] == URDF


def test_database(sim):
    """-database sends the original's include (the simulator finds the model: ode_sim's
    test_spawn_pose.py), with the name and pose of the request."""
    rc, out = spawn(sim, '-sdf', '-database', 'crate', '-model', 'crate1', '-x', '1', '-y', '2',
                    '-Y', '0.5')
    assert rc == 0, out
    req = sim.requests(service='/gazebo/spawn_sdf_model', model_name='crate1')[0]
    assert req['model_xml'] == ('<sdf version="1.4">\n    <world name="default">\n'
                                '        <include>\n            <uri>model://crate</uri>\n'
                                '        </include>\n    </world>\n</sdf>')
    assert req['pose'] == pytest.approx([1, 2, 0, 0, 0, math.sin(0.25), math.cos(0.25)])


def test_invalid_xml_exits_1(sim):
    rc, out = spawn(sim, '-urdf', '-stdin', '-model', 'broken', stdin='<robot><link></robot>')
    assert rc == 1
    assert 'Invalid XML: mismatched tag' in out and 'Traceback' not in out
    assert not sim.requests(model_name='broken')


def test_missing_file_and_param_exit_1(sim, tmp_path):
    rc, out = spawn(sim, '-urdf', '-file', str(tmp_path / 'nope.urdf'), '-model', 'm')
    assert rc == 1 and 'nope.urdf does not exist' in out and 'Traceback' not in out
    rc, out = spawn(sim, '-urdf', '-param', 'no_such_param', '-model', 'm')
    assert rc == 1 and 'param no_such_param does not exist or is empty' in out
    assert 'Traceback' not in out


def test_failed_spawn_exits_1(sim):
    rc, out = spawn(sim, '-urdf', '-stdin', '-model', 'bad_robot', '-J', 'axle', '1', stdin=URDF)
    assert rc == 1
    assert 'fake: refusing model bad_robot' in out and 'Spawn service failed. Exiting.' in out
    assert sim.requests(model_name='bad_robot', service='/gazebo/spawn_urdf_model')
    assert not sim.requests(model_name='bad_robot', service='/gazebo/set_model_configuration')


def test_wait_for_model(sim, tmp_path):
    waiter = Proc(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-param', '/robot_description',
                   '-model', 'waiter', '-wait', 'table'], env=sim.env,
                  log=str(tmp_path / 'waiter.log'))
    try:
        wait_for(lambda: 'Waiting for model table' in waiter.output(), 120,
                 what='spawn_model -wait to start waiting')
        time.sleep(1.0)
        assert waiter.alive() and not sim.requests(model_name='waiter')
        rc, out = spawn(sim, '-urdf', '-stdin', '-model', 'table', stdin=URDF)
        assert rc == 0, out
        wait_for(lambda: not waiter.alive(), 120, what='spawn_model -wait to finish')
        assert waiter.popen.returncode == 0, waiter.output()
        assert sim.requests(model_name='waiter', service='/gazebo/spawn_urdf_model')
    finally:
        waiter.stop()


@pytest.mark.parametrize('sig', [signal.SIGTERM, signal.SIGINT])
def test_bond_deletes_model_when_killed(sim, tmp_path, sig):
    name = 'bonded_%d' % sig
    proc = Proc(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-stdin', '-model', name, '-b'],
                env=sim.env, stdin=subprocess.PIPE, log=str(tmp_path / 'bond.log'))
    try:
        proc.popen.stdin.write(URDF.encode())
        proc.popen.stdin.close()
        wait_for(lambda: 'Waiting for shutdown to delete model' in proc.output(), 120,
                 what='spawn_model -b to spawn')
        assert proc.alive() and not sim.requests(service='/gazebo/delete_model', model_name=name)
        os.kill(proc.pid, sig)
        proc.popen.wait(60)       # a hang bound: deleting the model takes a service call
        assert proc.popen.returncode == 0, proc.output()
        assert sim.requests(service='/gazebo/delete_model', model_name=name), proc.output()
    finally:
        proc.stop()
