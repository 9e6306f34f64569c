"""sim_node for real: a roscore, the node on a world file, every /gazebo service driven by a
client process; bad worlds and bad robots give one clear line."""
import json
import math
import os
import subprocess

import pytest

from course_testing import Proc, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
PKG = os.path.dirname(HERE)

WORLD = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="default">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
    {extra}
  </world>
</sdf>
"""


def call(cmd, env, timeout=60):
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)


def write_world(tmp_path, extra='', name='w.world'):
    path = tmp_path / name
    path.write_text(WORLD.format(extra=extra))
    return str(path)


def sim(roscore, world, tmp_path, *args):
    subprocess.run(['rosparam', 'set', '/use_sim_time', 'true'], env=roscore.env, check=True,
                   timeout=120)
    return Proc(['rosrun', 'ode_sim', 'sim_node', world] + list(args), env=roscore.env,
                log=str(tmp_path / 'sim.log'))


def test_every_gazebo_service(roscore, tmp_path):
    world = write_world(tmp_path)
    node = sim(roscore, world, tmp_path, '-u')
    try:
        cone = os.path.join(PKG, 'models', 'traffic_cone', 'model.sdf')
        res = call(['python3', os.path.join(HERE, 'sim_client.py'), 'api', cone], roscore.env, 120)
        assert res.returncode == 0, res.stdout + res.stderr + node.output()
        out = json.loads(res.stdout.strip().splitlines()[-1])
    finally:
        node.stop()
    log = node.output()
    assert out['paused_still'], 'time ran while started with -u'
    assert out['spawn'] == [True, 'SpawnModel: Successfully spawned entity']
    assert out['spawn_dup'] == [False, 'SpawnModel: Failure - entity already exists.']
    ok, msg = out['spawn_zero_mass']
    assert not ok and "link 'arm'" in msg and 'mass' in msg, msg
    ok, msg = out['spawn_broken']
    assert not ok and 'malformed XML' in msg, msg
    assert out['spawn_sdf'][0], out['spawn_sdf']
    assert out['spawn_rel'][0] and out['spawn_rel'][1][:2] == pytest.approx([-2, 1], abs=1e-3)
    assert out['arm_paused']['xyz'] == pytest.approx([1, 2, 0.1], abs=1e-6)
    assert set(out['world']) == {'ground_plane', 'arm', 'cone', 'cone_rel'}
    assert out['props'] == [['base', 'arm'], ['shoulder'], False]
    assert out['running']
    assert out['arm_settled']['xyz'][2] == pytest.approx(0.1, abs=0.01)   # rests on the ground
    assert out['relative']['xyz'][:2] == pytest.approx([3, 2], abs=0.02)  # arm seen from cone
    assert {'ground_plane', 'arm', 'cone'} <= set(out['model_states'])
    assert {'arm::base', 'arm::arm', 'cone::link'} <= set(out['link_states'])
    assert out['config'][0], out['config']
    qz, qw = out['arm_link_q'][2:]
    assert 2 * math.atan2(qz, qw) == pytest.approx(1.0, abs=0.02)
    assert out['config_bad'][0] is False and "no joint 'elbow'" in out['config_bad'][1]
    assert out['set_state'][0] and out['set_state'][1] == pytest.approx([4, -1, 0.1], abs=0.01)
    # gazebo_ros_api_plugin's text (the model's name goes to the log)
    assert out['set_state_ghost'] == [False, 'SetModelState: model does not exist']
    assert out['set_state_topic'][:2] == pytest.approx([-3, 0], abs=0.05)
    assert out['wrench'] and out['pushed'][1] > 0.05
    assert out['physics'][:3] == pytest.approx([0.001, 1000, -9.8])
    assert out['fast_running'], 'sim time stood still with max_update_rate 0'
    t0, t1, t2, t3 = out['step_change']
    assert t1 == pytest.approx(t0, abs=1e-9), 'sim time jumped when the step changed'
    assert t2 > t1 and t3 == pytest.approx(t2, abs=1e-9), out['step_change']
    assert out['reset_world'][0] == pytest.approx([1, 2, 0.1], abs=0.01) and out['reset_world'][1]
    assert out['reset_sim_time'] < 0.5
    assert out['paused_again']
    assert out['delete'] == [True, False]
    assert out['delete_again'][0] is False and 'does not exist' in out['delete_again'][1]
    assert "link 'arm'" in log           # the refused robot is named in the node's log


@pytest.mark.parametrize('extra, expect', [
    ('<model name="m"><link name="l"><collision name="c"><geometry><box>'
     '<size>1 1</size></box></geometry></collision></link>', 'malformed XML'),
    ('<include><uri>model://no_such_model</uri></include>', 'no_such_model'),
    ('<model name="m"><link name="l"><inertial><mass>1</mass></inertial><collision name="c">'
     '<geometry><mesh><uri>file:///nonexistent/thing.stl</uri></mesh></geometry></collision>'
     '</link></model>', 'thing.stl'),
])
def test_bad_world_exits_with_one_line(roscore, tmp_path, extra, expect):
    world = write_world(tmp_path, extra)
    res = call(['rosrun', 'ode_sim', 'sim_node', world], roscore.env, 60)
    assert res.returncode == 1
    lines = [l for l in res.stderr.splitlines() if l.startswith('sim_node: error:')]
    assert len(lines) == 1 and expect in lines[0], res.stderr
    assert 'Traceback' not in res.stderr


def test_missing_world_file(roscore, tmp_path):
    res = call(['rosrun', 'ode_sim', 'sim_node', 'worlds/nonexistent.world'], roscore.env, 60)
    assert res.returncode == 1 and 'nonexistent.world' in res.stderr
    assert 'Traceback' not in res.stderr


def test_unknown_plugin_warns_and_the_world_runs(roscore, tmp_path):
    extra = ('<model name="m"><pose>0 0 1 0 0 0</pose><link name="l"><inertial><mass>1</mass>'
             '</inertial><collision name="c"><geometry><sphere><radius>0.1</radius></sphere>'
             '</geometry></collision></link>'
             '<plugin name="p" filename="libgazebo_ros_teleporter.so"/></model>')
    world = write_world(tmp_path, extra)
    node = sim(roscore, world, tmp_path)
    try:
        wait_for(lambda: 'libgazebo_ros_teleporter.so' in node.output(), 30, 0.2,
                 'the unknown-plugin warning')
        res = call(['rosservice', 'call', '/gazebo/get_model_state', 'm', ''], roscore.env, 30)
        assert 'success: True' in res.stdout
    finally:
        node.stop()
    log = node.output()
    assert "unknown plugin 'libgazebo_ros_teleporter.so'" in log
    assert 'libgazebo_ros_diff_drive.so' in log          # the known ones are listed


class FakeClock:
    """Wall time that moves only when the simulator works (`cost` per step) or sleeps."""

    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t

    def sleep(self, s):
        self.t += s


def paced_run(rate, steps, cost, stall_at=None, stall=0.0):
    from ode_sim.ros.node import Pacer
    clock = FakeClock()
    pacer = Pacer(clock, clock.sleep)
    pacer.restart(rate, 0)
    start = clock()
    for k in range(1, steps + 1):
        clock.t += cost + (stall if k == stall_at else 0.0)
        if not pacer.after_step(k):
            pacer.restart(rate, k)
    return clock() - start, pacer


def test_pacing_follows_gazebo_update_rate():
    """1 ms steps at real_time_update_rate 1000 take one wall second per sim second, however
    fast a step is; rate 0 never waits (pacing policy on an injected clock: no wall-clock
    threshold in the gate; bench/sim_pacing measures the real thing)."""
    wall, pacer = paced_run(1000.0, 2000, cost=0.0001)
    assert wall == pytest.approx(2.0, abs=0.002) and pacer.resyncs == 0
    wall, pacer = paced_run(500.0, 1000, cost=0.0001)      # 0.5x real time
    assert wall == pytest.approx(2.0, abs=0.002)
    wall, pacer = paced_run(0.0, 2000, cost=0.0001)        # as fast as possible
    assert wall == pytest.approx(0.2) and pacer.slept == 0.0
    wall, pacer = paced_run(1000.0, 2000, cost=0.002)      # a step slower than its period
    assert wall == pytest.approx(4.0) and pacer.slept == 0.0


def test_pacing_does_not_race_to_catch_up_after_a_stall():
    """A 3 s stall of the machine (swap, a loaded CI runner): the simulator restarts its count
    instead of running the missed 3000 steps unpaced, then keeps real time again."""
    wall, pacer = paced_run(1000.0, 2000, cost=0.0001, stall_at=500, stall=3.0)
    assert pacer.resyncs == 1
    assert wall == pytest.approx(2.0 + 3.0, abs=0.01)
