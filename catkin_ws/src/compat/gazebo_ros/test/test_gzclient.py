"""gzclient is the simulator's window (ode_sim_gui): headless one line and exit 0; on a display
a window titled "Gazebo" that registers as the launch's node, draws the simulator's world, and
closes with one line when the simulator exits; `gazebo` runs the server and the window."""
import os
import signal
import subprocess
import time

import pytest

from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb
from gazebo_ros import gzclient

WORLD = """<?xml version="1.0"?>
<sdf version="1.6"><world name="default">
  <light name="sun" type="directional"><direction>-0.5 0.1 -0.9</direction>
    <diffuse>0.8 0.8 0.8 1</diffuse></light>
  <model name="red_block"><static>true</static><pose>0 0 0.75 0 0 0</pose><link name="link">
    <collision name="c"><geometry><box><size>1.5 1.5 1.5</size></box></geometry></collision>
    <visual name="v"><geometry><box><size>1.5 1.5 1.5</size></box></geometry>
      <material><ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual>
  </link></model>
</world></sdf>
"""


def red_pixels(path):
    rgb = load_rgb(path).astype(int)
    r, g, b = rgb[:, :, 0], rgb[:, :, 1], rgb[:, :, 2]
    return int(((r > 120) & (g < 0.35 * r) & (b < 0.35 * r)).sum())


def window_names(display):
    out = subprocess.run(['xwininfo', '-display', display, '-root', '-tree'],
                         capture_output=True, text=True, timeout=20).stdout
    return out


@pytest.mark.parametrize('qpa', [None, 'offscreen'])
def test_headless_one_line_exit_0(roscore, qpa):
    # also with the test runner's QT_QPA_PLATFORM=offscreen: no window without a display
    env = dict(roscore.env)
    env.pop('DISPLAY', None)
    env.pop('QT_QPA_PLATFORM', None)
    if qpa:
        env['QT_QPA_PLATFORM'] = qpa
    out = subprocess.run(['rosrun', 'gazebo_ros', 'gzclient', '__name:=gazebo_gui'], env=env,
                         capture_output=True, text=True, timeout=30)
    assert out.returncode == 0
    assert out.stdout.splitlines() == ['[INFO] ' + gzclient.NO_DISPLAY]
    assert out.stderr == ''


def wait_red(display, shot, proc, count=2000, timeout=120):
    deadline = time.monotonic() + timeout
    n = 0
    while time.monotonic() < deadline and n < count:
        assert proc.alive(), proc.output()[-3000:]
        time.sleep(1.0)
        screenshot(display, shot)
        n = red_pixels(shot)
    assert n >= count, 'the red block is not drawn (%d red pixels)' % n


def test_window_draws_the_world_and_closes_with_the_simulator(roscore, screen, tmp_path):
    env = dict(roscore.env, DISPLAY=screen.display)
    env.pop('QT_QPA_PLATFORM', None)
    world = tmp_path / 'red.world'
    world.write_text(WORLD)
    # the window first: it waits for the simulator, as gzclient waits for gzserver
    client = Proc(['rosrun', 'gazebo_ros', 'gzclient', '__name:=gazebo_gui'], env=env,
                  log=str(tmp_path / 'gzclient.log'))
    sim = Proc(['rosrun', 'ode_sim', 'sim_node', str(world)], env=env,
               log=str(tmp_path / 'sim.log'))
    try:
        wait_red(screen.display, str(tmp_path / 'gzclient.png'), client)
        assert '"Gazebo"' in window_names(screen.display)
        nodes = subprocess.run(['rosnode', 'list'], env=env, capture_output=True, text=True,
                               timeout=20).stdout.split()
        assert '/gazebo_gui' in nodes
        # the simulator exits: the window closes with one line, exit 0
        sim.stop()
        wait_for(lambda: not client.alive(), 60, what='the window to close')
        assert client.popen.returncode == 0
        assert ('[INFO] gzclient: the simulator (/gazebo) has exited; closing the window'
                in client.output().splitlines())
    finally:
        client.stop()
        sim.stop()


def test_gazebo_runs_server_and_window(roscore, screen, tmp_path):
    env = dict(roscore.env, DISPLAY=screen.display)
    env.pop('QT_QPA_PLATFORM', None)
    world = tmp_path / 'red.world'
    world.write_text(WORLD)
    both = Proc(['rosrun', 'gazebo_ros', 'gazebo', str(world)], env=env,
                log=str(tmp_path / 'gazebo.log'))
    try:
        wait_red(screen.display, str(tmp_path / 'gazebo.png'), both)
        nodes = subprocess.run(['rosnode', 'list'], env=env, capture_output=True, text=True,
                               timeout=20).stdout.split()
        assert '/gazebo' in nodes
        assert any(n.startswith('/gzclient') for n in nodes), nodes
        # closing the window (here: its process ends) stops the server too, as Gazebo's
        os.killpg(both.pid, signal.SIGINT)
        wait_for(lambda: not both.alive(), 60, what='gazebo to stop')
        nodes = subprocess.run(['rosnode', 'list'], env=env, capture_output=True, text=True,
                               timeout=20).stdout.split()
        assert '/gazebo' not in nodes and not any(n.startswith('/gzclient') for n in nodes)
    finally:
        both.stop()
