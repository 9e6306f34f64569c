"""gazebo_ros_control_node with ode_sim in lockstep: two runs of the same scenario give
identical joint trajectories; the node lives and dies with the simulator."""
import json
import os
import signal
import subprocess
import time

import pytest

from course_testing import Proc, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
XACRO = os.path.join(HERE, 'rig.urdf.xacro')
YAML = os.path.join(HERE, 'rig_control.yaml')
NODE = 'gazebo_ros_control_node'


def sh(cmd, env, timeout=60, check=True):
    r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)
    if check:
        assert r.returncode == 0, '%s failed: %s%s' % (' '.join(cmd), r.stdout, r.stderr)
    return r.stdout


def children(pid, name):
    """PIDs of live processes whose parent is pid and whose command name starts with name."""
    out = []
    for d in os.listdir('/proc'):
        if not d.isdigit():
            continue
        try:
            with open('/proc/%s/stat' % d) as f:
                stat = f.read()
        except OSError:
            continue
        comm = stat[stat.index('(') + 1:stat.rindex(')')]
        fields = stat[stat.rindex(')') + 2:].split()
        if int(fields[1]) == pid and name.startswith(comm) and fields[0] != 'Z':
            out.append(int(d))
    return out


def gone(pid):
    try:
        with open('/proc/%d/stat' % pid) as f:
            return f.read().rsplit(')', 1)[1].split()[0] in ('Z', 'X')
    except OSError:
        return True


def start_sim(env, tmp_path, tag, mode='true'):
    """sim_node --lockstep -u (paused) with the rig spawned; returns (sim Proc, node pid or
    None for the in-process controller manager)."""
    urdf = tmp_path / ('rig_%s.urdf' % mode)
    urdf.write_text(sh(['xacro', XACRO, 'controller_node:=' + mode], env))
    sim = Proc(['rosrun', 'ode_sim', 'sim_node', '--lockstep', '-u'], env=env,
               log=str(tmp_path / ('sim_%s.log' % tag)))
    sh(['rosparam', 'set', '/use_sim_time', 'true'], env)
    sh(['rosparam', 'load', YAML, '/rig'], env)
    sh(['rosparam', 'set', '/robot_description', '-t', str(urdf)], env)
    sh(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-param', 'robot_description', '-model', 'rig'],
       env, timeout=120)
    if mode == 'inprocess':
        return sim, None
    nodes = wait_for(lambda: children(sim.pid, NODE), 60, 0.1,
                     'gazebo_ros_control_node started by the simulator\n' + sim.output()[-2000:])
    return sim, nodes[0]


@pytest.fixture
def env(roscore):
    e = dict(roscore.env)
    e.pop('DISPLAY', None)
    return e


def run_scenario(env, tmp_path, tag, mode='true'):
    """Paused sim, controllers spawned (switch pending), unpause: the tilt arm sags under
    gravity against its PID from t=0; 2 s of /rig/joint_states."""
    sim, _ = start_sim(env, tmp_path, tag, mode)
    spawner = rec = None
    try:
        spawner = Proc(['rosrun', 'controller_manager', 'spawner', 'joint_state_controller',
                        'tilt_position_controller', 'swing_position_controller', '--namespace', '/rig',
                        '--timeout', '90'], env=env, log=str(tmp_path / ('spawner_%s.log' % tag)))
        wait_for(lambda: 'Loaded controllers' in spawner.output(), 90, 0.1,
                 'the spawner loading the controllers\n' + spawner.output()[-2000:])
        time.sleep(1.0)     # let the spawner's switch request reach the (paused) manager
        rec = Proc(['python3', os.path.join(HERE, 'record_states.py'), '2.0'], env=env,
                   log=str(tmp_path / ('rec_%s.log' % tag)))
        wait_for(lambda: 'recording' in rec.output(), 60, 0.1, 'the recorder')
        wait_for(lambda: '/record_states' in sh(['rostopic', 'info', '/rig/joint_states'], env), 60, 0.2,
                 'the recorder subscribed')
        sh(['rosservice', 'call', '/gazebo/unpause_physics'], env)
        line = wait_for(lambda: next((l for l in rec.output().splitlines() if l.startswith('[')), None),
                        120, 0.2, 'the recording\n' + sim.output()[-2000:])
        assert 'lockstep: no joint command' not in sim.output(), sim.output()[-3000:]
        return json.loads(line)
    finally:
        for p in (rec, spawner):
            if p is not None:
                p.stop()
        sim.stop()


def assert_same_trajectory(a, b):
    """Identical joint states at every stamp both recordings have. joint_state_controller's
    realtime publisher skips a cycle when its thread is still busy (as upstream), so which
    50 Hz samples get out depends on the machine; the states themselves must not."""
    sa = {row[0]: row for row in a}
    sb = {row[0]: row for row in b}
    common = sorted(set(sa) & set(sb))
    assert len(common) >= 0.8 * min(len(a), len(b)), \
        'too few common samples: %d of %d / %d' % (len(common), len(a), len(b))
    for t in common:
        assert sa[t] == sb[t], 'runs differ at t=%.3f: %s vs %s' % (t * 1e-9, sa[t], sb[t])


@pytest.mark.parametrize('mode', ['true', 'inprocess'])
def test_two_runs_identical(env, tmp_path, mode):
    a = run_scenario(env, tmp_path, 'a', mode)
    b = run_scenario(env, tmp_path, 'b', mode)
    assert a[0][0] == b[0][0], 'the controllers started at different sim times: %s vs %s ns' % (a[0][0], b[0][0])
    assert a[0][0] < 0.05e9, 'joint_state_controller did not start at the first update: %s ns' % a[0][0]
    n = min(len(a), len(b))
    assert n >= 90, 'too few joint_states in 2 s of sim time: %d' % n
    tilt = a[0][1].index('tilt_joint')
    sag = [row[2][tilt] for row in a[:n]]
    assert max(abs(x) for x in sag) > 0.01, 'the tilt arm should sag under gravity: %s' % sag[:10]
    assert_same_trajectory(a, b)


def test_inprocess_same_trajectory_as_child_process(env, tmp_path):
    """The controller manager in the simulator's process gives the lockstep child's result."""
    a = run_scenario(env, tmp_path, 'p', 'true')
    b = run_scenario(env, tmp_path, 'i', 'inprocess')
    n = min(len(a), len(b))
    assert n >= 90 and a[0][0] == b[0][0], (a[:2], b[:2])
    assert_same_trajectory(a, b)


def test_node_exits_with_simulator(env, tmp_path):
    # the simulator stops normally (SIGINT): the plugin stops the node
    sim, node = start_sim(env, tmp_path, 'int')
    sim.popen.send_signal(signal.SIGINT)
    wait_for(lambda: gone(node), 30, 0.1, 'the node exiting after the simulator stopped')
    sim.stop()
    # the simulator dies (SIGKILL): the node notices its parent is gone
    sim, node = start_sim(env, tmp_path, 'kill')
    try:
        os.kill(sim.pid, signal.SIGKILL)
        wait_for(lambda: gone(node), 30, 0.1, 'the node exiting after the simulator was killed')
    finally:
        sim.stop()
        if not gone(node):
            os.kill(node, signal.SIGKILL)


def test_inprocess_does_not_receive_its_own_clock(env, tmp_path):
    """The in-process controller manager gets the sim time from each step (ros::Time::setNow
    in grc_update), so its roscpp does not subscribe to the /clock its own process publishes;
    and the simulator runs it: the controllers load, start and publish stamped joint states."""
    import rosgraph
    sim, _ = start_sim(env, tmp_path, 'clock', 'inprocess')
    spawner = None
    try:
        master = rosgraph.Master('/test_lockstep', master_uri=env['ROS_MASTER_URI'])
        subs = dict(master.getSystemState()[1])
        assert any(n.startswith('/gazebo_ros_control') for ns in subs.values() for n in ns), subs
        assert not [n for n in subs.get('/clock', []) if n.startswith('/gazebo')], subs['/clock']
        sh(['rosservice', 'call', '/gazebo/unpause_physics'], env)
        spawner = Proc(['rosrun', 'controller_manager', 'spawner', 'joint_state_controller',
                        '--namespace', '/rig', '--timeout', '90'], env=env,
                       log=str(tmp_path / 'spawner_clock.log'))
        out = sh(['rostopic', 'echo', '-n', '1', '/rig/joint_states/header/stamp'], env,
                 timeout=120)
        assert 'secs' in out and out.strip() != 'secs: 0\nnsecs:         0', out
    finally:
        if spawner is not None:
            spawner.stop()
        sim.stop()
