"""Practical work 6 replayed as a student does it (textbook chapter 7): camera and lidar.

`catkin_create_pkg my_robot_simulation_sensors rospy std_msgs`, the chapter's launch file and
RViz config (from the reference package catkin_ws/src/course/my_robot_simulation_sensors), the
text's own `sensor_data_proc.py` listing, `catkin build`; the model where the text puts it
($(find my_robot_simulation)/diff_drive_robot/urdf/diff_drive_robot.xacro) through `xacro` and
`check_urdf`; then `roslaunch my_robot_simulation_sensors robot_sim_camera.launch gui:=false
rviz:=false`: /diff_drive_robot/laser and /diff_drive_robot/camera1/image_raw arrive with the
configured sizes, `rostopic echo` of single fields works, and the student's script publishes
Canny edges of the camera image.
"""
import importlib.util
import os

import pytest

from course_testing import sim_testing as T

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell_6', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

PKG = 'my_robot_simulation_sensors'
HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(S.REPO, 'catkin_ws', 'src', 'course', PKG)
STARTER = os.path.join(HERE, 'task_6', 'starter', PKG)
README = os.path.join(HERE, 'task_6', 'README.md')
FILES = {'launch': ['robot_sim_camera.launch'],
         'config': ['sensors.rviz']}


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    ws = S.make_workspace(tmp_path_factory.mktemp('task6'))
    pkg, out = S.create_package(ws, PKG, ['rospy', 'std_msgs'], ['launch', 'config', 'scripts'],
                                REFERENCE, FILES)
    S.write_script(os.path.join(pkg, 'scripts', 'sensor_data_proc.py'),
                   S.readme_listing(README, '#!/usr/bin/env python3\nimport os'))
    build = S.catkin_build(ws)
    return dict(ws=ws, pkg=pkg, env=S.overlay_env(ws), create_out=out, build=build)


def test_starter_layout():
    with open(os.path.join(STARTER, 'package.xml')) as f:
        xml = f.read()
    for dep in ('my_robot_simulation', 'cv_bridge', 'gazebo_ros', 'sensor_msgs'):
        assert '<exec_depend>%s</exec_depend>' % dep in xml


def test_model_with_sensors(workspace, tmp_path):
    env, urdf = workspace['env'], str(tmp_path)
    assert S.sh(['rospack', 'find', PKG], env).strip() == workspace['pkg']
    S.sh("rosrun xacro xacro $(rospack find my_robot_simulation)/diff_drive_robot/urdf/diff_drive_robot.xacro"
         " > diff_drive_robot.urdf", env, cwd=urdf)
    out = S.sh(['check_urdf', 'diff_drive_robot.urdf'], env, cwd=urdf)
    assert 'root Link: base_link has 5 child(ren)' in out and 'camera' in out and 'lidar' in out, out
    with open(os.path.join(urdf, 'diff_drive_robot.urdf')) as f:
        text = f.read()
    assert 'libgazebo_ros_camera.so' in text and 'libgazebo_ros_laser.so' in text
    assert 'libgazebo_ros_diff_drive.so' in text


def test_camera_lidar_and_edges(workspace, roscore, tmp_path):
    env = S.with_master(workspace['env'], roscore)
    env.pop('DISPLAY', None)
    p = S.launch(['roslaunch', PKG, 'robot_sim_camera.launch', 'gui:=false', 'rviz:=false'], env,
                 tmp_path / 'launch.log')
    try:
        scan = T.probe(['topic', '/diff_drive_robot/laser'], env, proc=p)
        assert scan['samples'] == 720 and scan['frame_id'] == 'lidar', scan
        out = S.sh(['rostopic', 'echo', '-n', '1', '/diff_drive_robot/laser/angle_min'], env, timeout=30)
        assert float(out.split()[0]) == pytest.approx(-0.785, abs=1e-3)
        img = T.probe(['topic', '/diff_drive_robot/camera1/image_raw', '--save', tmp_path / 'camera.png'], env, proc=p)
        assert (img['width'], img['height'], img['encoding']) == (600, 400, 'rgb8'), img
        out = S.sh(['rostopic', 'echo', '-n', '1', '/sensor_data_proc/edges/width'], env, timeout=60)
        assert out.split()[0] == '600'
        edges = T.probe(['topic', '/sensor_data_proc/edges', '--save', tmp_path / 'edges.png'], env, proc=p)
        assert (edges['height'], edges['encoding']) == (400, 'mono8'), edges
        assert edges['nonzero'] > 200, 'no edges in the camera image %s (mean %.1f): %s' % (
            tmp_path / 'camera.png', img['mean'], edges)
        S.wait_output(p, 'edge pixels', timeout=30)
    finally:
        p.stop()
