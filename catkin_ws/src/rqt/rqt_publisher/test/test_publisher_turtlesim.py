"""Message Publisher drives turtlesim (practical 5 §6.3 with turtlesim's cmd_vel in place of the
position controller): Xvfb + private roscore; a bad field expression is reported in its cell and
the other fields are still published."""
import os
import subprocess
import sys

import pytest
from course_testing import Proc, wait_for
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))


def pose(env):
    out = subprocess.run(['rostopic', 'echo', '-n', '1', '/turtle1/pose'], env=env, capture_output=True,
                         text=True, timeout=60).stdout
    return {l.split(':')[0].strip(): float(l.split(':')[1]) for l in out.splitlines()
            if ':' in l and l.split(':')[0].strip() in ('x', 'y', 'theta')}


@pytest.mark.full
def test_message_publisher_drives_turtlesim(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    procs = []
    try:
        procs.append(Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=env, log=str(tmp_path / 'sim.log')))
        before = pose(env)
        assert before, 'no /turtle1/pose from turtlesim'
        gui = Proc([sys.executable, os.path.join(HERE, 'check_publisher_driver.py')], env=env,
                   log=str(tmp_path / 'publisher.log'))
        procs.append(gui)
        wait_for(lambda: not gui.alive(), 90, 0.2, 'rqt_publisher to finish')
        got = {s.get('kind'): s for s in states(gui.output())}
        assert gui.popen.returncode == 0 and 'done' in got, gui.output()[-3000:]
        after = pose(env)
    finally:
        for p in reversed(procs):
            p.stop()
    assert got['enabled']['bad_cell'] == 'not a number # error evaluating as "float64"'
    assert 'error evaluating as "float64"' in got['enabled']['status']
    assert got['done']['counter'] >= 10
    moved = ((after['x'] - before['x']) ** 2 + (after['y'] - before['y']) ** 2) ** 0.5
    assert moved > 0.5, 'the turtle moved only %.2f m' % moved
    assert abs(after['theta'] - before['theta']) > 0.2
