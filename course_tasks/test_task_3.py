"""Practical work 3 replayed as a student does it (textbook chapter 4): URDF, xacro, RViz.

`catkin_create_pkg my_robot_model rospy std_msgs roscpp`, the folders scripts/launch/urdf, the
course's model files (reference: catkin_ws/src/course/my_robot_model), `catkin build`,
`rosrun xacro xacro ... > f.urdf`, `check_urdf f.urdf`, `roslaunch my_robot_model robot.launch`
(headless: /robot_description and /tf; and with RViz under Xvfb, screenshot checked), and
`rosrun tf2_tools view_frames.py` (Debian's replacement for `rosrun tf view_frames`).
"""
import importlib.util
import os
import re
import subprocess
import time

import pytest

from course_testing import Xvfb, screenshot, wait_for

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell_3', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

PKG = 'my_robot_model'
REFERENCE = os.path.join(S.REPO, 'catkin_ws', 'src', 'course', PKG)
STARTER = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'task_3', 'starter', PKG)
LINKS = {'base_link', 'wheel_left', 'wheel_right', 'caster'}


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """Section 4.1: catkin_create_pkg, mkdir scripts launch urdf, the model files, catkin build."""
    if not os.path.isdir(REFERENCE):
        pytest.fail('the reference package %s is missing' % REFERENCE)
    ws = S.make_workspace(tmp_path_factory.mktemp('task3'))
    pkg, out = S.create_package(
        ws, PKG, ['rospy', 'std_msgs', 'roscpp'], ['scripts', 'launch', 'urdf', 'models'], REFERENCE,
        {'urdf': ['my_first_model.urdf', 'diff_robot_model.urdf.xacro', 'materials.xacro',
                  'wheel.xacro', 'inertial.xacro', 'rviz_conf.rviz'],
         'launch': ['robot.launch', 'first_model.launch'],
         'models': ['base_frame.stl']})
    build = S.catkin_build(ws)
    return dict(ws=ws, pkg=pkg, env=S.overlay_env(ws), create_out=out, build=build)


def test_starter_matches_the_chapter_layout():
    for d in ('scripts', 'launch', 'urdf'):
        assert os.path.isdir(os.path.join(STARTER, d)), d
    with open(os.path.join(STARTER, 'package.xml')) as f:
        xml = f.read()
    assert '<name>my_robot_model</name>' in xml
    for dep in ('xacro', 'robot_state_publisher', 'joint_state_publisher', 'rviz'):
        assert '<exec_depend>%s</exec_depend>' % dep in xml


def test_package_builds_and_is_found(workspace):
    assert 'Successfully created files' in workspace['create_out']
    assert S.sh(['rospack', 'find', PKG], workspace['env']).strip() == workspace['pkg']


def test_xacro_to_urdf_and_check_urdf(workspace):
    env, urdf = workspace['env'], os.path.join(workspace['pkg'], 'urdf')
    S.sh('rosrun xacro xacro diff_robot_model.urdf.xacro > diff_robot_model.urdf', env, cwd=urdf)
    with open(os.path.join(urdf, 'diff_robot_model.urdf')) as f:
        text = f.read()
    assert 'package://my_robot_model/models/base_frame.stl' in text and 'xacro:' not in text
    out = S.sh(['check_urdf', 'diff_robot_model.urdf'], env, cwd=urdf)
    assert 'robot name is: my_robot' in out and 'Successfully Parsed XML' in out, out
    assert 'root Link: base_link has 3 child(ren)' in out, out
    for l in ('wheel_left', 'wheel_right', 'caster'):
        assert 'child(%d):  %s' % (sorted(LINKS - {'base_link'}).index(l) + 1, l) in out or l in out
    out = S.sh(['check_urdf', 'my_first_model.urdf'], env, cwd=urdf)
    assert 'Successfully Parsed XML' in out and 'root Link: base_link' in out, out


def test_xacro_error_is_one_clear_line(workspace):
    """Section 1.12: finding errors in xacro. A broken file gives a message, not a traceback."""
    env, urdf = workspace['env'], os.path.join(workspace['pkg'], 'urdf')
    with open(os.path.join(urdf, 'diff_robot_model.urdf.xacro')) as f:
        text = f.read()
    with open(os.path.join(urdf, 'broken.urdf.xacro'), 'w') as f:
        f.write(text.replace('</robot>', ''))
    rc, out, err = S.sh_rc(['rosrun', 'xacro', 'xacro', 'broken.urdf.xacro'], env, cwd=urdf)
    assert rc != 0 and out.strip() == ''
    assert 'Traceback' not in err and 'broken.urdf.xacro' in err, err


def test_robot_launch_headless(workspace, roscore, tmp_path):
    """robot.launch without RViz: robot_description from xacro, the TF of every link."""
    env = S.with_master(workspace['env'], roscore)
    p = S.launch(['roslaunch', PKG, 'robot.launch', 'rviz:=false', 'gui:=false'], env, tmp_path / 'launch.log')
    try:
        probe = '''
import rospy, yaml
from tf2_msgs.msg import TFMessage
rospy.init_node('probe', anonymous=True)
frames = set()
def cb(m):
    for t in m.transforms:
        frames.add((t.header.frame_id, t.child_frame_id))
rospy.Subscriber('/tf', TFMessage, cb); rospy.Subscriber('/tf_static', TFMessage, cb)
deadline = rospy.get_time() + 40
while not rospy.is_shutdown() and rospy.get_time() < deadline and len(frames) < 3:
    rospy.sleep(0.2)
rospy.sleep(1.0)
desc = rospy.get_param('/robot_description', '')
print(yaml.safe_dump({'frames': sorted(list(f) for f in frames), 'desc': desc[:20000]},
                     default_flow_style=True, width=10**9))
'''
        res = S.run_probe(probe, env, timeout=90)
    finally:
        p.stop()
    assert '<robot name="my_robot"' in res['desc'] and 'base_frame.stl' in res['desc']
    pairs = {tuple(f) for f in res['frames']}
    assert {('base_link', 'wheel_left'), ('base_link', 'wheel_right'), ('base_link', 'caster')} <= pairs, pairs


def test_robot_launch_with_rviz_and_view_frames(workspace, roscore, tmp_path):
    """robot.launch as written (RViz with rviz_conf.rviz) under Xvfb: the orange body is drawn;
    then `rosrun tf2_tools view_frames.py` writes frames.pdf with every link."""
    xvfb = Xvfb(1600, 1000)
    xvfb.start()
    p = None
    try:
        env = S.with_master(workspace['env'], roscore, xvfb)
        p = S.launch(['roslaunch', PKG, 'robot.launch'], env, tmp_path / 'launch.log')
        # RViz is up once its display manager subscribes to /tf
        wait_for(lambda: '/rviz' in S.sh(['rostopic', 'info', '/tf'], env, check=False).split('Subscribers:')[-1]
                 or (not p.alive() and pytest.fail('roslaunch exited: ' + p.output()[-2000:])),
                 60, 1.0, 'rviz subscribing to /tf')
        shot = str(tmp_path / 'rviz.png')

        def orange_pixels():
            assert p.alive(), p.output()[-2000:]
            screenshot(xvfb.display, shot)
            hist = subprocess.run(['convert', shot, '-format', '%c', 'histogram:info:-'],
                                  stdout=subprocess.PIPE, check=True, timeout=60).stdout.decode()
            orange = 0
            for m in re.finditer(r'^\s*(\d+):\s*\(\s*(\d+),\s*(\d+),\s*(\d+)', hist, re.M):
                n, r, g, b = (int(x) for x in m.groups())
                if r > 120 and 0.25 * r < g < 0.65 * r and b < 0.25 * r:
                    orange += n
            return orange
        # screenshots until RViz has drawn the robot (later on a busy machine; a hang guard)
        deadline = time.monotonic() + 90
        orange = orange_pixels()
        while orange <= 2000 and time.monotonic() < deadline:
            time.sleep(1.0)
            orange = orange_pixels()
        assert orange > 2000, 'only %d orange pixels in %s' % (orange, shot)
        out = S.sh(['rosrun', 'tf2_tools', 'view_frames.py'], env, cwd=str(tmp_path), timeout=60)
        assert os.path.getsize(tmp_path / 'frames.pdf') > 1000, out
        with open(tmp_path / 'frames.gv') as f:
            gv = f.read()
        for l in LINKS:
            assert '"%s"' % l in gv, gv
    finally:
        if p is not None:
            p.stop()
        xvfb.stop()
