"""Robot Steering drives turtlesim (Xvfb + private roscore): the turtle's pose changes while the
linear slider is at 1.0 m/s and the angular one at 0.5 rad/s."""
import os
import subprocess
import sys

from course_testing import Proc, wait_for
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))


def pose(env):
    out = subprocess.run(['rostopic', 'echo', '-n', '1', '/turtle1/pose'], env=env, capture_output=True,
                         text=True, timeout=60).stdout
    return {l.split(':')[0].strip(): float(l.split(':')[1]) for l in out.splitlines()
            if ':' in l and l.split(':')[0].strip() in ('x', 'y', 'theta', 'linear_velocity')}


def test_steering_drives_turtlesim(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    procs = []
    try:
        procs.append(Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=env, log=str(tmp_path / 'sim.log')))
        before = pose(env)
        assert before, 'no /turtle1/pose from turtlesim'
        gui = Proc([sys.executable, os.path.join(HERE, 'check_steering_driver.py')], env=env,
                   log=str(tmp_path / 'steering.log'))
        procs.append(gui)
        wait_for(lambda: any(s.get('kind') == 'driving' for s in states(gui.output())) or not gui.alive(),
                 60, 0.2, 'rqt_robot_steering to start driving')
        wait_for(lambda: not gui.alive(), 60, 0.2, 'rqt_robot_steering to finish')
        got = {s.get('kind'): s for s in states(gui.output())}
        assert gui.popen.returncode == 0 and 'stopped' in got, gui.output()[-3000:]
        after = pose(env)
    finally:
        for p in reversed(procs):
            p.stop()
    assert got['driving'] == {'kind': 'driving', 'linear': '1.00 m/s', 'angular': '0.50 rad/s',
                              'topic': '/turtle1/cmd_vel'}
    assert got['stopped']['linear'] == '0.00 m/s'
    moved = ((after['x'] - before['x']) ** 2 + (after['y'] - before['y']) ** 2) ** 0.5
    assert moved > 0.5, 'the turtle moved only %.2f m (before %s, after %s)' % (moved, before, after)
    assert abs(after['theta'] - before['theta']) > 0.2
