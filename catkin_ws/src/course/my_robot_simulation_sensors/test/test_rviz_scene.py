"""RViz for real under Xvfb: the practical-work scene (my_robot_simulation's my_scene.world) with
the sensor robot, as robot_sim_camera.launch opens it — the screenshot must show the robot, the
simulator's scene markers and the laser scan."""
import os
import subprocess

import numpy as np

from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb


def topic_has_message(env, topic):
    res = subprocess.run(['rostopic', 'echo', '-n', '1', topic], env=env, capture_output=True,
                         text=True, timeout=30)
    return res.returncode == 0 and res.stdout.strip()


def window_up(env, name):
    res = subprocess.run(['xwininfo', '-root', '-tree'], env=env, capture_output=True, text=True,
                         timeout=15)
    return name in res.stdout


def counts(img):
    """Pixel counts in RViz's 3D view (1600x1000 screen, the view centred on the robot)."""
    r, g, b = (img[..., i].astype(int) for i in range(3))
    scan = (r > 200) & (g < 60) & (b < 60)          # LaserScan: flat 255,0,0 squares
    orange = (r > 150) & (g > 50) & (g < 150) & (b < 60)
    centre = np.zeros(scan.shape, bool)
    centre[380:560, 830:1020] = True                 # around the focal point: the robot
    view = np.zeros(scan.shape, bool)
    view[70:860, 370:1480] = True
    return {'scan': int((scan & view).sum()),
            # the robot's orange body (Gazebo/Orange) at the focal point
            'robot': int((orange & centre).sum()),
            # scene markers away from the robot: the traffic cone (orange)
            'scene_orange': int((orange & view & ~centre).sum())}


def test_rviz_shows_robot_scene_markers_and_scan(roscore, screen, tmp_path):
    env = dict(roscore.env)
    env['DISPLAY'] = screen.display
    launch = Proc(['roslaunch', 'my_robot_simulation_sensors', 'robot_sim_camera.launch',
                   'gui:=false', 'proc:=false'], env=env, log=str(tmp_path / 'launch.log'))
    try:
        wait_for(lambda: topic_has_message(env, '/scan'), 90, 1.0, 'a LaserScan on /scan')
        wait_for(lambda: topic_has_message(env, '/gazebo/scene_markers'), 60, 1.0,
                 'scene markers')
        wait_for(lambda: window_up(env, 'RViz'), 60, 1.0, 'the RViz window')
        shot = str(tmp_path / 'rviz.png')

        def drawn():
            screenshot(screen.display, shot)
            c = counts(load_rgb(shot))
            return c if c['scan'] > 30 and c['scene_orange'] > 300 else None
        c = wait_for(drawn, 60, 2.0, 'RViz drawing the scan and the scene markers')
    finally:
        launch.stop()
    assert c['robot'] > 300, c
    keep = os.environ.get('KEEP_SCREENSHOTS')
    if keep:
        import shutil
        shutil.copy(shot, os.path.join(keep, 'pw6_rviz_scene.png'))
