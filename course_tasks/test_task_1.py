"""Practical work 1 replayed as a student does it (textbook chapter 2).

roscore; rospy_tutorials talker/listener; turtlesim_node with rostopic list/type/echo/hz/pub and
rosmsg show; turtle_teleop_key; rqt_plot of /turtle1/pose; a catkin workspace (`catkin init`,
`catkin build`, also `catkin_make`) with the starter package my_robot_controller, then the
publisher and subscriber of sections 2.10-2.11.
"""
import importlib.util
import math
import os
import pty
import re
import select
import shutil
import time

import pytest

from course_testing import screenshot, wait_for

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

TASK = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'task_1')
STARTER = os.path.join(TASK, 'starter', 'my_robot_controller')
REFERENCE = os.path.join(TASK, 'reference', 'my_robot_controller')
CENTRE = 11.088889 / 2          # turtlesim's first turtle starts in the middle of the field


def _load_script(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# --------------------------------------------------------------------------- workspace


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """Sections 2.7-2.11: workspace, starter package, catkin build, then the student's nodes."""
    ws = S.make_workspace(tmp_path_factory.mktemp('task1'))
    shutil.copytree(STARTER, os.path.join(ws, 'src', 'my_robot_controller'))
    out = S.catkin_build(ws)
    assert 'All 2 packages succeeded' in out or 'succeeded' in out, out
    # the student writes my_publisher.py and my_subscriber.py and lists them in CMakeLists.txt
    pkg = os.path.join(ws, 'src', 'my_robot_controller')
    for name in ('my_publisher.py', 'my_subscriber.py'):
        shutil.copy2(os.path.join(REFERENCE, 'scripts', name), os.path.join(pkg, 'scripts', name))
    shutil.copy2(os.path.join(REFERENCE, 'CMakeLists.txt'), os.path.join(pkg, 'CMakeLists.txt'))
    S.catkin_build(ws)
    return ws, S.overlay_env(ws)


def test_workspace_layout_and_config(workspace):
    ws, env = workspace
    for d in ('src', 'build', 'devel', 'logs'):
        assert os.path.isdir(os.path.join(ws, d)), d
    out = S.sh(['catkin', 'config'], env, cwd=ws)
    assert 'Workspace:' in out and ws in out
    assert S.sh(['rospack', 'find', 'my_robot_controller'], env).strip() == \
        os.path.join(ws, 'src', 'my_robot_controller')
    out = S.sh(['catkin', 'list'], env, cwd=ws)
    assert 'my_robot_controller' in out


def test_starter_package_files():
    assert sorted(os.listdir(STARTER)) == ['CMakeLists.txt', 'package.xml', 'scripts']
    node = os.path.join(STARTER, 'scripts', 'my_first_node.py')
    assert os.access(node, os.X_OK)
    with open(node) as f:
        assert f.readline().strip() == '#!/usr/bin/env python3'


def test_starter_node_runs(workspace, roscore, tmp_path):
    ws, env = workspace
    env = S.with_master(env, roscore)
    node = S.launch(['rosrun', 'my_robot_controller', 'my_first_node.py'], env, tmp_path / 'n.log')
    try:
        S.wait_output(node, 'Hello from my_robot_controller!')
        S.wait_output(node, 'tick 2')
        assert '/my_first_node' in S.sh(['rosnode', 'list'], env)
    finally:
        node.stop()


def test_reference_publisher_and_subscriber(workspace, roscore, tmp_path):
    """Sections 2.10-2.11: `rosrun` the two nodes in separate terminals; they exchange messages."""
    ws, env = workspace
    env = S.with_master(env, roscore)
    pub = S.launch(['rosrun', 'my_robot_controller', 'my_publisher.py'], env, tmp_path / 'p.log')
    sub = S.launch(['rosrun', 'my_robot_controller', 'my_subscriber.py'], env, tmp_path / 's.log')
    try:
        S.wait_output(pub, 'hello world')
        out = S.wait_output(sub, 'I heard hello world')
        stamp = float(out.split('I heard hello world ')[1].split()[0])
        assert abs(stamp - time.time()) < 60
        assert S.sh(['rostopic', 'type', '/chatter'], env).strip() == 'std_msgs/String'
        twist = S.echo_once('/cmd_vel', env)
        assert twist['linear']['x'] == 1.0 and twist['angular']['z'] == 0.0
        info = S.sh(['rostopic', 'info', '/chatter'], env)
        assert '/talker_' in info and '/listener_' in info
    finally:
        S.stop_all(pub, sub)


def test_reference_pure_functions():
    mod = _load_script(os.path.join(REFERENCE, 'scripts', 'my_publisher.py'), 't1_publisher')
    assert mod.make_greeting(12.5) == 'hello world 12.5'
    t = mod.make_forward_twist()
    assert (t.linear.x, t.linear.y, t.angular.z) == (1.0, 0.0, 0.0)
    assert mod.make_forward_twist(0.3).linear.x == 0.3


def test_catkin_make_workspace(tmp_path):
    """The same package built the classic way: `catkin_make` in a plain workspace."""
    ws = tmp_path / 'catkin_ws'
    (ws / 'src').mkdir(parents=True)
    shutil.copytree(REFERENCE, str(ws / 'src' / 'my_robot_controller'))
    env = S.shell_env()
    out = S.sh(['catkin_make', '-DPYTHON_EXECUTABLE=/usr/bin/python3'], env, cwd=str(ws), timeout=600)
    assert 'Built target' in out or 'Build files have been written' in out, out[-2000:]
    assert (ws / 'src' / 'CMakeLists.txt').exists()      # catkin_make's top-level toplevel.cmake link
    env = S.overlay_env(str(ws))
    assert S.sh(['rospack', 'find', 'my_robot_controller'], env).strip() == \
        str(ws / 'src' / 'my_robot_controller')
    assert 'my_publisher.py' in S.sh('ls "$(rospack find my_robot_controller)/scripts"', env)


# --------------------------------------------------------------------------- ready-made packages


def test_talker_listener(roscore, tmp_path):
    """Section 2.3: rosrun rospy_tutorials talker / listener in two terminals."""
    env = S.with_master(S.shell_env(), roscore)
    talker = S.launch(['rosrun', 'rospy_tutorials', 'talker'], env, tmp_path / 'talker.log')
    listener = S.launch(['rosrun', 'rospy_tutorials', 'listener'], env, tmp_path / 'listener.log')
    try:
        S.wait_output(talker, 'hello world')
        S.wait_output(listener, 'I heard hello world')
        # Ctrl+C on the talker: the listener stops receiving
        talker.stop()
        said = re.findall(r'hello world (\S+)', talker.output())
        # what the talker said before it stopped may still be on its way (a busy machine): wait
        # for its last line (10 s at most: a message cut by the Ctrl+C never comes)
        deadline = time.monotonic() + 10
        while ('I heard hello world %s' % said[-1]) not in listener.output() \
                and time.monotonic() < deadline:
            time.sleep(0.1)
        n = listener.output().count('I heard')
        time.sleep(1.5)
        assert listener.output().count('I heard') == n
        assert listener.alive()
    finally:
        S.stop_all(talker, listener)


@pytest.fixture
def turtlesim(roscore, xvfb, tmp_path):
    """`rosrun turtlesim turtlesim_node` on a private master and display; yields (env, proc)."""
    env = S.with_master(S.shell_env(), roscore, xvfb)
    sim = S.launch(['rosrun', 'turtlesim', 'turtlesim_node'], env, tmp_path / 'turtlesim.log')
    try:
        S.wait_topic('/turtle1/pose', env, proc=sim)
        yield env, sim
    finally:
        sim.stop()


def _pose(env):
    return S.echo_once('/turtle1/pose', env)


def test_turtlesim_topics_and_messages(turtlesim):
    env, _ = turtlesim
    topics = S.sh(['rostopic', 'list'], env).split()
    for t in ('/turtle1/cmd_vel', '/turtle1/pose', '/turtle1/color_sensor', '/rosout'):
        assert t in topics, topics
    assert S.sh(['rostopic', 'type', '/turtle1/cmd_vel'], env).strip() == 'geometry_msgs/Twist'
    assert S.sh(['rostopic', 'type', '/turtle1/pose'], env).strip() == 'turtlesim/Pose'
    pose_def = S.sh(['rosmsg', 'show', 'turtlesim/Pose'], env).split('\n')
    assert [l for l in pose_def if l] == ['float32 x', 'float32 y', 'float32 theta',
                                          'float32 linear_velocity', 'float32 angular_velocity']
    twist_def = S.sh(['rosmsg', 'show', 'geometry_msgs/Twist'], env)
    assert 'geometry_msgs/Vector3 linear' in twist_def and 'float64 z' in twist_def
    pose = _pose(env)
    assert pose['x'] == pytest.approx(CENTRE, abs=1e-3)
    assert pose['y'] == pytest.approx(CENTRE, abs=1e-3)
    assert pose['theta'] == 0.0


def test_rostopic_hz(turtlesim, tmp_path):
    env, _ = turtlesim
    hz = S.launch(['rostopic', 'hz', '/turtle1/pose'], env, tmp_path / 'hz.log')
    try:
        out = S.wait_output(hz, 'average rate:', timeout=30)
        rate = float(out.split('average rate:')[1].split()[0])
        assert 20.0 < rate < 100.0, rate     # turtlesim publishes every 16 ms tick (62.5 Hz)
    finally:
        hz.stop()


def test_rostopic_pub_moves_turtle(turtlesim):
    """Section 2.4: rostopic pub to /turtle1/cmd_vel makes the turtle drive an arc."""
    env, _ = turtlesim
    S.sh(['rostopic', 'pub', '-1', '/turtle1/cmd_vel', 'geometry_msgs/Twist',
          '{linear: {x: 2.0, y: 0.0, z: 0.0}, angular: {x: 0.0, y: 0.0, z: 1.8}}'], env, timeout=30)

    def stopped_after_moving():
        p = _pose(env)
        return p if p['linear_velocity'] == 0.0 and p['x'] != pytest.approx(CENTRE, abs=0.05) else None
    pose = wait_for(stopped_after_moving, 60, 0.2, 'the turtle to move and stop')
    moved = math.hypot(pose['x'] - CENTRE, pose['y'] - CENTRE)
    assert 0.3 < moved < 2.5, pose          # ~1 s of an arc of radius 2/1.8 m
    assert pose['theta'] > 0.5, pose        # turned left


def test_teleop_key_drives_turtle(turtlesim, tmp_path):
    """Section 2.4: rosrun turtlesim turtle_teleop_key; the up arrow drives the turtle forward."""
    env, _ = turtlesim
    master_fd, slave_fd = pty.openpty()
    teleop = None
    try:
        teleop = S.Proc(['rosrun', 'turtlesim', 'turtle_teleop_key'], env=env,
                        stdin=slave_fd, stdout=slave_fd)
        os.close(slave_fd)
        slave_fd = None
        banner = b''
        deadline = time.monotonic() + 30
        while b'arrow keys' not in banner and time.monotonic() < deadline:
            r, _, _ = select.select([master_fd], [], [], 0.5)
            if r:
                banner += os.read(master_fd, 4096)
        assert b'arrow keys' in banner, banner
        x0 = _pose(env)['x']

        def pressed_up():
            os.write(master_fd, b'\x1b[A')
            return _pose(env)['x'] > x0 + 0.3
        wait_for(pressed_up, 60, 0.2, 'the turtle to drive forward after the up arrow')
        os.write(master_fd, b'q')
    finally:
        if teleop:
            teleop.stop()
        os.close(master_fd)
        if slave_fd is not None:
            os.close(slave_fd)


def test_rqt_plot_of_pose(turtlesim, xvfb, tmp_path):
    """Section 2.4: rosrun rqt_plot rqt_plot /turtle1/pose shows a live plot."""
    env, _ = turtlesim
    plot = S.launch(['rosrun', 'rqt_plot', 'rqt_plot', '/turtle1/pose'], env, tmp_path / 'plot.log')
    try:
        S.sh(['rostopic', 'pub', '-1', '/turtle1/cmd_vel', 'geometry_msgs/Twist',
              '{linear: {x: 2.0}, angular: {z: 1.8}}'], env, timeout=30)

        def plotted():
            if not plot.alive():
                raise AssertionError('rqt_plot exited:\n' + plot.output()[-2000:])
            info = S.sh(['rostopic', 'info', '/turtle1/pose'], env)
            return 'Subscribers:' in info and 'None' not in info.split('Subscribers:')[1]
        wait_for(plotted, 30, 0.3, 'rqt_plot to subscribe /turtle1/pose')
        png = str(tmp_path / 'rqt_plot.png')

        def drawn():        # screenshots until it has drawn (later on a busy machine)
            screenshot(xvfb.display, png)
            return S.unique_colours(png) > 20
        wait_for(drawn, 60, 0.5, 'rqt_plot to draw (more than 20 colours on the screen)')
        if os.environ.get('COURSE_SHOTS_DIR'):     # keep the picture to look at it
            shutil.copy(png, os.path.join(os.environ['COURSE_SHOTS_DIR'], 'task1_rqt_plot.png'))
    finally:
        plot.stop()
