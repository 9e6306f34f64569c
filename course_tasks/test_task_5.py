"""Practical work 5 replayed as a student does it (textbook chapter 6): ros_control.

`catkin_create_pkg my_robot_simulation_control roscpp rospy std_msgs`, the folders, the
dependencies (the starter's package.xml / CMakeLists.txt), the chapter's files (the reference
package catkin_ws/src/course/my_robot_simulation_control stands for what the student types from
the text), `catkin build`, `roslaunch my_robot_simulation_control robot_sim_control.launch
gui:=false`, `rostopic pub -1 /diffrobot/joint1_position_controller/command ... "data: 1.5"`,
then self-study 1: the wheels by velocity (`robot_sim_velocity.launch` and `rosrun
controller_manager spawner … --namespace /diffrobot`), all headless on a private roscore and
judged on sim time.
"""
import importlib.util
import os
import shutil
import time

import pytest

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell_5', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

PKG = 'my_robot_simulation_control'
HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(S.REPO, 'catkin_ws', 'src', 'course', PKG)
STARTER = os.path.join(HERE, 'task_5', 'starter', PKG)
README = os.path.join(HERE, 'task_5', 'README.md')
FILES = {'urdf': ['diff_robot_model.urdf.xacro', 'materials.xacro', 'inertial.xacro', 'wheel.xacro',
                  'robot_control.gazebo'],
         'worlds': ['empty.world'],
         'models': ['base_frame.stl'],
         'config': ['diff_control.yaml', 'diff_velocity.yaml'],
         'launch': ['robot_sim_control.launch', 'robot_sim_velocity.launch']}
WALL = 120.0

# joint_states at sim time >= T as {'t': ..., 'position': [...], 'velocity': [...]}
STATE_AFTER = r'''
import json, sys, time, rospy
from sensor_msgs.msg import JointState
rospy.init_node('task5_probe', anonymous=True)
want = rospy.Time.now().to_sec() + float(sys.argv[1])
got = []
rospy.Subscriber('/diffrobot/joint_states', JointState, got.append)
end = time.monotonic() + %f
while time.monotonic() < end and not (got and got[-1].header.stamp.to_sec() >= want):
    time.sleep(0.05)
m = got[-1] if got else None
print(json.dumps({'t': m.header.stamp.to_sec(), 'name': list(m.name), 'position': list(m.position),
                      'velocity': list(m.velocity), 'want': want} if m else None))
''' % WALL


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """Section 5.1-5.2: the package, the dependencies, the files, catkin build."""
    ws = S.make_workspace(tmp_path_factory.mktemp('task5'))
    pkg, out = S.create_package(ws, PKG, ['roscpp', 'rospy', 'std_msgs'],
                                ['launch', 'config', 'urdf', 'worlds', 'models', 'scripts'],
                                REFERENCE, FILES)
    for f in ('package.xml', 'CMakeLists.txt'):
        shutil.copy2(os.path.join(STARTER, f), os.path.join(pkg, f))
    build = S.catkin_build(ws)
    return dict(ws=ws, pkg=pkg, env=S.overlay_env(ws), create_out=out, build=build)


def state_after(env, seconds):
    import subprocess
    out = subprocess.run(['/usr/bin/python3', '-c', STATE_AFTER, str(seconds)], env=env,
                         capture_output=True, text=True, timeout=WALL + 30)
    import json
    res = json.loads(out.stdout.strip().splitlines()[-1]) if out.stdout.strip() else None
    assert res and res['t'] >= res['want'], 'no /diffrobot/joint_states %.1f s of sim time later: %s %s' % (
        seconds, res, out.stderr[-2000:])
    return res


def velocities_settle(env, want, tol=0.25, within=15.0):
    """Sample /diffrobot/joint_states every simulated second until every joint of `want`
    ({joint: velocity}) is within tol of it in two samples running, at most `within` simulated
    seconds. A velocity PID on a robot that is itself moving settles in a time that depends on
    when the command reached it, which the test does not choose; a bound in sim time does not
    depend on the machine's speed. Returns (settled, last state)."""
    ok_before, s = False, None
    for _ in range(int(within)):
        s = state_after(env, 1.0)
        v = dict(zip(s['name'], s['velocity']))
        ok = all(abs(v[j] - w) < tol for j, w in want.items())
        if ok and ok_before:
            return True, s
        ok_before = ok
    return False, s


def wait_running(env, names, proc):
    deadline = time.monotonic() + WALL
    out = ''
    while time.monotonic() < deadline:
        out = S.sh(['rosservice', 'call', '/diffrobot/controller_manager/list_controllers'], env,
                   timeout=30, check=False)
        if all(('name: "%s"' % n) in out for n in names) and out.count('state: "running"') >= len(names):
            return out
        time.sleep(0.5)
    raise AssertionError('controllers %s not running: %s\n--- launch log:\n%s' % (names, out, proc.output()[-3000:]))


def test_starter_layout():
    for d in ('launch', 'config', 'urdf', 'worlds', 'models', 'scripts'):
        assert os.path.isdir(os.path.join(STARTER, d)), d
    with open(os.path.join(STARTER, 'package.xml')) as f:
        xml = f.read()
    for dep in ('controller_manager', 'joint_state_controller', 'effort_controllers', 'gazebo_ros_control'):
        assert '<exec_depend>%s</exec_depend>' % dep in xml


def test_readme_listings_match_the_reference():
    """The text's YAML and launch listings are the reference package's files."""
    yaml_text = S.readme_listing(README, 'diffrobot:')
    with open(os.path.join(REFERENCE, 'config', 'diff_control.yaml')) as f:
        assert yaml_text.strip() == f.read().strip()
    launch = S.readme_listing(README, '<launch>')
    for line in ('type="spawner"', 'ns="/diffrobot"', '--timeout 60', 'spawn_model',
                 'empty_world.launch'):
        assert line in launch, line


def test_position_control(workspace, roscore, tmp_path):
    env = S.with_master(workspace['env'], roscore)
    assert S.sh(['rospack', 'find', PKG], env).strip() == workspace['pkg']
    p = S.launch(['roslaunch', PKG, 'robot_sim_control.launch', 'gui:=false'], env, tmp_path / 'pc.log')
    try:
        wait_running(env, ['joint1_position_controller', 'joint2_position_controller',
                           'joint_state_controller'], p)
        S.sh(['rostopic', 'pub', '-1', '/diffrobot/joint1_position_controller/command',
              'std_msgs/Float64', 'data: 1.5'], env, timeout=60)
        s = state_after(env, 5.0)
        q = dict(zip(s['name'], s['position']))
        assert abs(q['wheel_left_joint'] - 1.5) < 0.02, s
        assert abs(q['wheel_right_joint']) < 0.05, s
    finally:
        p.stop()


def test_velocity_control(workspace, roscore, tmp_path):
    env = S.with_master(workspace['env'], roscore)
    p = S.launch(['roslaunch', PKG, 'robot_sim_velocity.launch', 'gui:=false'], env, tmp_path / 'vc.log')
    try:
        wait_running(env, ['joint1_velocity_controller', 'joint2_velocity_controller',
                           'joint_state_controller'], p)
        for c in ('joint1_velocity_controller', 'joint2_velocity_controller'):
            S.sh(['rostopic', 'pub', '-1', '/diffrobot/%s/command' % c, 'std_msgs/Float64', 'data: 5.0'],
                 env, timeout=60)
        ok, s = velocities_settle(env, {'wheel_left_joint': 5.0, 'wheel_right_joint': 5.0})
        assert ok, s
        # the controllers by hand: stop one with the controller_manager CLI, spawn it again
        S.sh(['rosrun', 'controller_manager', 'controller_manager', 'stop', 'joint1_velocity_controller'],
             dict(env, ROS_NAMESPACE='/diffrobot'), timeout=60)
        S.sh(['rosrun', 'controller_manager', 'controller_manager', 'unload', 'joint1_velocity_controller'],
             dict(env, ROS_NAMESPACE='/diffrobot'), timeout=60)
        sp = S.launch(['rosrun', 'controller_manager', 'spawner', 'joint1_velocity_controller',
                       '--namespace', '/diffrobot'], env, tmp_path / 'spawner.log')
        try:
            S.wait_output(sp, 'Started controllers', 90)
            S.sh(['rostopic', 'pub', '-1', '/diffrobot/joint1_velocity_controller/command',
                  'std_msgs/Float64', 'data: -3.0'], env, timeout=60)
            ok, s = velocities_settle(env, {'wheel_left_joint': -3.0})
            assert ok, s
        finally:
            sp.stop()
    finally:
        p.stop()
