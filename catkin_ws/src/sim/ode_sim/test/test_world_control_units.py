"""ode_sim.ros.world_control without a roscore: step_world's exact step count in the node's step
groups, the real-time factor, the statistics and pose messages (test_world_control.py drives
the real node)."""
import threading

import pytest

from ode_sim.description import sdf
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.world_control import RealTimeFactor, WorldControl


class FakeNode:
    """The part of SimNode that WorldControl uses, on a real PhysicsWorld."""

    def __init__(self, group=7, dt=0.001):
        world = sdf.parse_world('<sdf version="1.6"><world name="w"><physics type="ode">'
                                '<max_step_size>%r</max_step_size></physics></world></sdf>'
                                % dt, 'w.world')
        self.physics = PhysicsWorld(world.physics, world.gravity)
        self.paused = True
        self.lock = threading.RLock()
        self.group = group
        self.calls = []
        self.clock_forced = 0

    def group_size(self):
        return self.group

    def step_once(self, n=1):
        self.calls.append(n)
        self.physics.step(n)

    def publish_clock(self, force=False):
        self.clock_forced += force


def control(node):
    wc = WorldControl.__new__(WorldControl)     # no services: no roscore needed
    wc.node, wc.api = node, None
    wc.start_wall, wc.pause_time, wc.rtf = 100.0, 0.0, RealTimeFactor()
    return wc


@pytest.mark.parametrize('steps, group, calls', [
    (100, 7, [7] * 14 + [2]), (1, 50, [1]), (120, 50, [50, 50, 20]), (3, 1, [1, 1, 1])])
def test_step_exactly_n_in_step_groups(steps, group, calls):
    node = FakeNode(group)
    node.physics.step(5)
    wc = control(node)
    t0, k0 = node.physics.time, node.physics.steps
    ok, msg = wc.step(steps)
    assert ok, msg
    assert node.calls == calls
    assert node.physics.steps == k0 + steps
    assert node.physics.time == pytest.approx(t0 + steps * 0.001, abs=1e-12)
    assert node.clock_forced == 1


def test_step_refused_while_running():
    node = FakeNode()
    node.paused = False
    ok, msg = control(node).step(10)
    assert not ok and 'pause it first' in msg
    assert node.physics.steps == 0 and node.calls == []


def test_real_time_factor_over_the_window():
    rtf = RealTimeFactor(window=1.0)
    assert rtf.value() == 0.0
    for i in range(21):                 # 0.1 s of wall per 0.05 s of sim: 0.5
        rtf.add(10.0 + 0.1 * i, 0.05 * i)
    assert rtf.value() == pytest.approx(0.5)
    assert rtf.samples[-1][0] - rtf.samples[0][0] <= 1.1
    rtf.add(12.1, 0.0)                  # reset_simulation: time went back
    assert rtf.value() == 0.0
    rtf.add(12.6, 1.0)
    assert rtf.value() == pytest.approx(2.0)


def test_statistics_message():
    node = FakeNode(dt=0.002)
    wc = control(node)
    node.physics.step(250)
    wc.pause_time = 3.5
    m = wc.stats(wall=110.0)
    assert m.sim_time.to_sec() == pytest.approx(0.5) and m.iterations == 250
    assert m.real_time.to_sec() == pytest.approx(10.0) and m.pause_time.to_sec() == 3.5
    assert m.paused and m.real_time_factor == 0.0 and m.max_step_size == 0.002
    node.paused = False
    node.physics.step(500)
    m = wc.stats(wall=111.0)
    assert not m.paused and m.real_time_factor == pytest.approx(1.0)


def test_pose_info_every_model_and_link():
    node = FakeNode()
    box = sdf.parse_sdf_model(
        '<sdf version="1.6"><model name="b"><pose>1 2 3 0 0 0.5</pose>'
        '<link name="l1"><inertial><mass>1</mass></inertial></link>'
        '<link name="l2"><pose>0 0 1 0 0 0</pose><inertial><mass>1</mass></inertial></link>'
        '<joint name="j" type="fixed"><parent>l1</parent><child>l2</child></joint>'
        '</model></sdf>', 'b')
    node.physics.add_model(box)
    node.physics.step(3)
    m = control(node).pose_info()
    assert m.iterations == 3 and m.sim_time.to_sec() == pytest.approx(0.003)
    assert m.model_name == ['b'] and m.link_name == ['b::l1', 'b::l2']
    p = m.model_pose[0].position
    assert [p.x, p.y, p.z] == pytest.approx([1, 2, 3 - 0.5 * 9.8 * 0.003 ** 2 * 2], abs=1e-4)
    assert m.link_pose[1].position.z - m.link_pose[0].position.z == pytest.approx(1.0, abs=1e-6)
    assert m.model_pose[0].orientation.z == pytest.approx(0.2474, abs=1e-3)
