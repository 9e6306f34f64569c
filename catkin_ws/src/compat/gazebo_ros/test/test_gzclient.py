"""gzclient: headless it says where the scene is and exits 0; with a display it is RViz on
ode_sim's config/scene.rviz, which shows /gazebo/scene_markers in the odom frame."""
import os
import subprocess
import time

import pytest

from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb
from gazebo_ros import gzclient


def test_command_line():
    env = {'DISPLAY': ':5'}
    assert gzclient.client_command(['--verbose', '__name:=gazebo_gui', '__log:=/x.log'], env,
                                   '/c/scene.rviz') == [
        'rviz', '-d', '/c/scene.rviz', '__name:=gazebo_gui', '__log:=/x.log']
    assert gzclient.client_command([], {}, '/c/scene.rviz') is None
    assert gzclient.client_command([], {'DISPLAY': ''}, '/c/scene.rviz') is None


def test_scene_config_exists():
    path = gzclient.scene_config()
    assert path.endswith('ode_sim/config/scene.rviz') and os.path.isfile(path)
    text = open(path).read()
    for needle in ('Fixed Frame: odom', 'Marker Topic: /gazebo/scene_markers', 'Topic: /scan',
                   'Image Topic: /camera/image_raw', 'Robot Description: robot_description'):
        assert needle in text


def test_headless_one_line_exit_0(roscore):
    env = dict(roscore.env)
    env.pop('DISPLAY', None)
    out = subprocess.run(['rosrun', 'gazebo_ros', 'gzclient', '__name:=gazebo_gui'], env=env,
                         capture_output=True, text=True, timeout=30)
    assert out.returncode == 0
    assert out.stdout.splitlines() == ['[INFO] ' + gzclient.NO_DISPLAY]
    assert out.stderr == ''


MARKER = ('markers: [{header: {frame_id: odom}, ns: test, id: 1, type: 1, action: 0, '
          'pose: {position: {x: 0, y: 0, z: 0.5}, orientation: {w: 1}}, '
          'scale: {x: 3, y: 3, z: 1}, color: {r: 1.0, g: 0.0, b: 0.0, a: 1.0}}]')


def red_pixels(path):
    rgb = load_rgb(path).astype(int)
    r, g, b = rgb[:, :, 0], rgb[:, :, 1], rgb[:, :, 2]
    return int(((r > 120) & (g < 0.35 * r) & (b < 0.35 * r)).sum())


def test_display_runs_rviz_on_the_scene(roscore, screen, tmp_path):
    env = dict(roscore.env, DISPLAY=screen.display)
    env.pop('QT_QPA_PLATFORM', None)
    client = Proc(['rosrun', 'gazebo_ros', 'gzclient', '__name:=gazebo_gui'], env=env,
                  log=str(tmp_path / 'gzclient.log'))
    pub = Proc(['rostopic', 'pub', '-r', '2', '/gazebo/scene_markers',
                'visualization_msgs/MarkerArray', MARKER], env=env,
               log=str(tmp_path / 'pub.log'))
    try:
        # exec: the same process is now RViz, on ode_sim's scene configuration
        def cmdline():
            with open('/proc/%d/cmdline' % client.pid, 'rb') as f:
                return f.read().split(b'\0')
        wait_for(lambda: b'-d' in cmdline(), 20, what='gzclient to exec rviz')
        argv = [a.decode() for a in cmdline() if a]
        assert os.path.basename(argv[0]) == 'rviz' or argv[0].endswith('/rviz'), argv
        assert argv[1:] == ['-d', gzclient.scene_config(), '__name:=gazebo_gui']
        shot = str(tmp_path / 'gzclient.png')
        deadline = time.monotonic() + 60
        count = 0
        while time.monotonic() < deadline and count < 2000:
            assert client.alive(), client.output()[-3000:]
            time.sleep(1.0)
            screenshot(screen.display, shot)
            count = red_pixels(shot)
        assert count >= 2000, 'the red scene marker is not drawn (%d red pixels)' % count
        nodes = subprocess.run(['rosnode', 'list'], env=env, capture_output=True, text=True,
                               timeout=20).stdout.split()
        assert '/gazebo_gui' in nodes
    finally:
        pub.stop()
        client.stop()
