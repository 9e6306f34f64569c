"""The textbook's launch files and PW6's sensor_data_proc.py, as printed (issue 29, section 1).

The files in course_tasks/book/ are the book's listings typed as printed (only the OCR's damage
undone: quotes, broken lines, `cameral` for `camera1`); see course_tasks/README.md for the table
listing -> file -> test. Each runs unchanged against the reference packages, on a private roscore
and a private X display (the book's files start RViz, the simulator's window and the joint
sliders unconditionally):

- PW3 (T §4.1-4.2) robot.launch with my_first_model.urdf and with diff_robot_model.urdf.xacro:
  robot_state_publisher publishes the wheels' TF, RViz stays up, `rosrun tf view_frames` draws it;
- PW4 (T §5.1) sim.launch: $(find my_robot_model)/urdf/diff_robot_model_done.urdf.xacro,
  .../urdf/rviz_conf.rviz and .../worlds/empty.world; the robot stands on the floor and drives
  on /cmd_vel;
- PW6 (T §7.1-7.2) robot_sim_camera.launch: $(find my_robot_simulation)/urdf/rviz_conf.rviz and
  .../diff_drive_robot/urdf/diff_drive_robot.xacro; /diff_drive_robot/laser has the book's lidar,
  and the book's sensor_data_proc.py (subscribing /diff_drive_robot/camera1/image_raw), run
  through rosrun, receives 600x400 frames and prints their shape.
"""
import importlib.util
import math
import os

import pytest

from course_testing import sim_testing as T

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell_book', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

BOOK = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'book')


def book_env(rviz_env):
    env = dict(S.shell_env(), **{k: rviz_env[k] for k in ('ROS_MASTER_URI', 'ROS_LOG_DIR', 'DISPLAY')
                                 if k in rviz_env})
    env.pop('QT_QPA_PLATFORM', None)
    env.pop('ROS_HOSTNAME', None)
    if 'ROS_IP' in rviz_env:
        env['ROS_IP'] = rviz_env['ROS_IP']
    return env


def roslaunch_book(name, env, tmp_path):
    path = os.path.join(BOOK, name)
    assert os.path.isfile(path), path
    return S.launch(['roslaunch', path], env, tmp_path / (name + '.log'))


def assert_all_alive(p, nodes):
    out = p.output()
    assert p.alive(), out[-3000:]
    assert 'process has died' not in out and 'Traceback' not in out, out[-3000:]
    for n in nodes:
        assert 'process[%s-' % n in out, 'node %s not started:\n%s' % (n, out[-3000:])


@pytest.mark.parametrize('name', ['pw3_first_model.launch', 'pw3_robot.launch'])
def test_pw3_robot_launch_as_printed(rviz_env, tmp_path, name):
    env = book_env(rviz_env)
    p = roslaunch_book(name, env, tmp_path)
    try:
        tf = S.wait_topic('/tf', env, timeout=120, proc=p)
        children = {t['child_frame_id'] for t in tf['transforms']}
        assert {'wheel_left', 'wheel_right'} <= children, tf
        static = S.wait_topic('/tf_static', env, timeout=60, proc=p)
        assert 'caster' in {t['child_frame_id'] for t in static['transforms']}, static
        S.wait_output(p, 'process[rviz-', timeout=30)
        if name == 'pw3_robot.launch':
            # T §4.2: `rosrun tf view_frames` draws the tree into frames.pdf (and frames.gv)
            out = S.sh(['rosrun', 'tf', 'view_frames'], env, cwd=tmp_path, timeout=120)
            assert 'frames.pdf generated' in out, out
            with open(tmp_path / 'frames.gv') as f:
                graph = f.read()
            assert '"wheel_left"' in graph and '"caster"' in graph, graph
        assert_all_alive(p, ['joint_state_publisher', 'robot_state_publisher', 'rviz'])
    finally:
        p.stop()


def test_pw4_sim_launch_as_printed(rviz_env, tmp_path):
    env = book_env(rviz_env)
    p = roslaunch_book('pw4_sim.launch', env, tmp_path)
    try:
        pose = T.probe(['model', 'my_robot_model', '--timeout', 120], env, timeout=180, proc=p)['pose']
        res = T.probe(['drive', 'my_robot_model', '--topic', '/cmd_vel', '--vx', 0.3, '--seconds', 2.0],
                      env, timeout=180, proc=p)
        b, a = res['before'], res['after']
        # spawned without -z: base_link of the done model lies on the floor, the robot stays there
        assert abs(pose['z']) < 0.01 and abs(b['z']) < 0.01 and abs(a['z']) < 0.01, res
        dist = math.hypot(a['x'] - b['x'], a['y'] - b['y'])
        assert 0.35 < dist < 0.75 and abs(a['y'] - b['y']) < 0.1, res      # 0.3 m/s for 2 s
        assert_all_alive(p, ['joint_state_publisher_gui', 'robot_state_publisher', 'gazebo',
                             'gazebo_gui', 'my_robot_model_spawn', 'rviz'])
    finally:
        p.stop()


def test_pw6_launch_and_sensor_data_proc_as_printed(rviz_env, tmp_path):
    env = book_env(rviz_env)
    # the book's script, typed into a package of the student's and started with rosrun (a package
    # of another name than the reference's my_robot_simulation_sensors: rosrun would ask which one)
    src = tmp_path / 'src'
    src.mkdir()
    S.sh(['catkin_create_pkg', 'my_sensors', 'rospy', 'std_msgs'], S.shell_env(), cwd=src)
    scripts = src / 'my_sensors' / 'scripts'
    scripts.mkdir()
    with open(os.path.join(BOOK, 'pw6_sensor_data_proc.py')) as f:
        text = f.read()
    assert '"/diff_drive_robot/camera1/image_raw"' in text
    S.write_script(str(scripts / 'sensor_data_proc.py'), text)
    student = dict(env, PATH='/usr/bin:/bin', ROS_PACKAGE_PATH='%s:%s' % (src, env['ROS_PACKAGE_PATH']))

    p = roslaunch_book('pw6_robot_sim_camera.launch', env, tmp_path)
    proc = None
    try:
        T.probe(['model', 'diff_drive_robot1', '--timeout', 120], env, timeout=180, proc=p)
        scan = T.probe(['topic', '/diff_drive_robot/laser'], env, timeout=180, proc=p)
        assert scan['samples'] == 720 and scan['frame_id'] == 'lidar', scan
        assert scan['angle_min'] == pytest.approx(-0.785, abs=1e-3)
        assert scan['angle_max'] == pytest.approx(0.785, abs=1e-3)
        assert (scan['range_min'], scan['range_max']) == (pytest.approx(0.03), pytest.approx(3.0)), scan
        info = T.probe(['topic', '/diff_drive_robot/camera1/camera_info'], env, timeout=180, proc=p)
        assert info['frame_id'] == 'camera', info
        proc = S.launch(['rosrun', 'my_sensors', 'sensor_data_proc.py'], student,
                        tmp_path / 'sensor_data_proc.log')
        out = S.wait_output(proc, '(400, 600, 3)', timeout=180)
        assert 'Traceback' not in out, out[-3000:]
        assert_all_alive(p, ['joint_state_publisher', 'robot_state_publisher', 'gazebo', 'gazebo_gui',
                             'my_robot_spawn', 'rviz'])
        assert proc.alive(), proc.output()[-3000:]
    finally:
        S.stop_all(proc, p)
