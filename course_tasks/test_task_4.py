"""Practical work 4 replayed as a student does it (textbook chapter 5): the robot in the simulator.

`catkin_create_pkg my_robot_simulation rospy std_msgs`, the folders, the chapter's files (the
reference package catkin_ws/src/course/my_robot_simulation stands for what the student types
from the text), `catkin build`, `xacro` + `check_urdf`, `roslaunch my_robot_simulation
sim.launch gui:=false rviz:=false`, `rostopic pub /cmd_vel`, `rosservice call
/gazebo/get_model_state`, `rosrun gazebo_ros spawn_model ... -x -y -z` (self-study 3) and the
text's own `move.py` listing (self-study 2), all headless on a private roscore.
"""
import importlib.util
import os
import shutil
import time

import pytest
import yaml

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell_4', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

PKG = 'my_robot_simulation'
HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(S.REPO, 'catkin_ws', 'src', 'course', PKG)
STARTER = os.path.join(HERE, 'task_4', 'starter', PKG)
README = os.path.join(HERE, 'task_4', 'README.md')
FILES = {'urdf': ['diff_robot_model.urdf.xacro', 'materials.xacro', 'wheel.xacro', 'robot_diff.gazebo'],
         'worlds': ['empty.world', 'my_scene.world'],
         'launch': ['sim.launch', 'scene.launch', 'sim_xyz.launch'],
         'config': ['sim.rviz'],
         'models': ['base_frame.stl']}


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """Section 4.1, steps 1-6: the package from the starter layout, the files, catkin build."""
    ws = S.make_workspace(tmp_path_factory.mktemp('task4'))
    pkg, out = S.create_package(ws, PKG, ['rospy', 'std_msgs'],
                                ['launch', 'urdf', 'worlds', 'config', 'scripts', 'models'],
                                REFERENCE, FILES)
    shutil.copy2(os.path.join(STARTER, 'urdf', 'inertial.xacro'), os.path.join(pkg, 'urdf'))
    S.write_script(os.path.join(pkg, 'scripts', 'move.py'),
                   S.readme_listing(README, '#!/usr/bin/env python3\n"""Drive forward'))
    build = S.catkin_build(ws)
    return dict(ws=ws, pkg=pkg, env=S.overlay_env(ws), create_out=out, build=build)


def model_state(env, name):
    """`rosservice call /gazebo/get_model_state '{model_name: NAME}'` as a dict."""
    out = S.sh(['rosservice', 'call', '/gazebo/get_model_state', '{model_name: %s}' % name], env, timeout=30)
    return yaml.safe_load(out)


def wait_model(env, name, proc, timeout=60.0):
    deadline = time.monotonic() + timeout
    last = None
    while time.monotonic() < deadline:
        out = S.sh(['rosservice', 'call', '/gazebo/get_model_state', '{model_name: %s}' % name], env,
                   timeout=30, check=False)
        try:
            last = yaml.safe_load(out)
        except yaml.YAMLError:
            last = out
        if isinstance(last, dict) and last.get('success'):
            return last
        time.sleep(0.5)
    raise AssertionError('model %s never appeared (%s)\n--- launch log:\n%s' % (name, last, proc.output()[-3000:]))


def sim_time(env):
    """`rosservice call /gazebo/get_world_properties`: the simulator's time."""
    out = S.sh(['rosservice', 'call', '/gazebo/get_world_properties'], env, timeout=30)
    return float(yaml.safe_load(out)['sim_time'])


def wait_sim(env, t_end, timeout=300.0):
    """Until the simulation reaches sim time T_END (the timeout is a hang guard): what the robot
    does meanwhile is the same on a slow or busy machine."""
    deadline = time.monotonic() + timeout
    while sim_time(env) < t_end:
        assert time.monotonic() < deadline, 'sim time did not reach %g' % t_end
        time.sleep(0.5)


def test_starter_layout():
    for d in ('launch', 'urdf', 'worlds', 'config', 'scripts', 'models'):
        assert os.path.isdir(os.path.join(STARTER, d)), d
    with open(os.path.join(STARTER, 'package.xml')) as f:
        xml = f.read()
    for dep in ('gazebo_ros', 'xacro', 'robot_state_publisher', 'rviz'):
        assert '<exec_depend>%s</exec_depend>' % dep in xml
    with open(os.path.join(STARTER, 'urdf', 'inertial.xacro')) as f:
        macros = f.read()
    for m in ('inertial_box', 'inertial_cylinder', 'inertial_sphere'):
        assert 'name="%s"' % m in macros


def test_package_builds_and_model_checks(workspace):
    env, urdf = workspace['env'], os.path.join(workspace['pkg'], 'urdf')
    assert 'Successfully created files' in workspace['create_out']
    assert S.sh(['rospack', 'find', PKG], env).strip() == workspace['pkg']
    S.sh('rosrun xacro xacro diff_robot_model.urdf.xacro > diff_robot_model.urdf', env, cwd=urdf)
    out = S.sh(['check_urdf', 'diff_robot_model.urdf'], env, cwd=urdf)
    assert 'root Link: base_link has 3 child(ren)' in out, out
    with open(os.path.join(urdf, 'diff_robot_model.urdf')) as f:
        text = f.read()
    assert text.count('<collision') == 4 and text.count('<inertial>') == 4
    assert 'libgazebo_ros_diff_drive.so' in text and '<mu1>0.0</mu1>' in text


def test_sim_launch_drive_and_spawn(workspace, roscore, tmp_path):
    env = S.with_master(workspace['env'], roscore)
    p = S.launch(['roslaunch', PKG, 'sim.launch', 'gui:=false', 'rviz:=false'], env, tmp_path / 'sim.log')
    pub = None
    try:
        start = wait_model(env, 'my_robot_model', p)
        topics = S.sh(['rostopic', 'list'], env).split()
        for t in ('/cmd_vel', '/odom', '/clock', '/gazebo/model_states', '/tf'):
            assert t in topics, (t, topics)
        # drive: rostopic pub -r 10 /cmd_vel ... for a while, then stop
        pub = S.launch(['rostopic', 'pub', '-r', '10', '/cmd_vel', 'geometry_msgs/Twist',
                        '{linear: {x: 0.3}, angular: {z: 0.0}}'], env, tmp_path / 'pub.log')
        odom = S.wait_topic('/odom', env, proc=p)
        assert odom['header']['frame_id'] == 'odom' and odom['child_frame_id'] == 'base_link'
        wait_sim(env, sim_time(env) + 4.0)     # 4 s of driving in sim time
        pub.stop()
        pub = None
        S.sh(['rostopic', 'pub', '-1', '/cmd_vel', 'geometry_msgs/Twist', '{}'], env, timeout=30)
        moved = model_state(env, 'my_robot_model')
        dx = moved['pose']['position']['x'] - start['pose']['position']['x']
        assert dx > 0.3, (start['pose'], moved['pose'])
        assert abs(moved['pose']['position']['y']) < 0.15
        states = S.echo_once('/gazebo/model_states', env)
        assert 'my_robot_model' in states['name'] and 'ground_plane' in states['name']
        # self-study 3: one more robot at given x, y, z
        out = S.sh(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-param', 'robot_description',
                    '-model', 'robot2', '-x', '1', '-y', '1', '-z', '0.3'], env, timeout=60)
        second = wait_model(env, 'robot2', p)
        assert abs(second['pose']['position']['x'] - 1) < 0.05 and abs(second['pose']['position']['y'] - 1) < 0.05, out
        # self-study 2: the text's move.py (drives both robots: they share /cmd_vel)
        before = model_state(env, 'my_robot_model')['pose']['position']['x']
        S.sh(['rosrun', PKG, 'move.py', '_speed:=0.3', '_duration:=2'], env, timeout=60)
        after = model_state(env, 'my_robot_model')['pose']['position']['x']
        assert after - before > 0.3, (before, after)
        assert model_state(env, 'robot2')['pose']['position']['x'] > 1.3
    finally:
        if pub is not None:
            pub.stop()
        p.stop()
