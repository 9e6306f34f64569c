"""Practical work 2 replayed as a student does it (textbook chapter 3).

`catkin_create_pkg my_super_robot_controller rospy std_msgs`, scripts/super_node.py, custom
messages (Num, Position2d) with message_generation/message_runtime, `rosmsg show`, the
position2d republisher, launch/my_setup.launch, two controllers in namespaces, and the
textbook's launch example with turtlesim's mimic node.
"""
import importlib.util
import math
import os
import shutil
import sys

import pytest

from course_testing import screenshot, wait_for

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

PKG = 'my_super_robot_controller'
REFERENCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'task_2', 'reference', PKG)
FIELD = 11.088889
CENTRE = FIELD / 2


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """Sections 3.1-3.4: create the package with catkin_create_pkg, fill it in, catkin build."""
    ws = S.make_workspace(tmp_path_factory.mktemp('task2'))
    src = os.path.join(ws, 'src')
    out = S.sh(['catkin_create_pkg', PKG, 'rospy', 'std_msgs'], S.shell_env(), cwd=src)
    pkg = os.path.join(src, PKG)
    created = sorted(os.listdir(pkg))
    with open(os.path.join(pkg, 'package.xml')) as f:
        generated_xml = f.read()
    # what catkin_create_pkg left for the student; then the student's edits (the reference)
    for d in ('scripts', 'msg', 'launch'):
        os.mkdir(os.path.join(pkg, d))
    with open(os.path.join(pkg, 'msg', 'Num.msg'), 'w') as f:
        f.write('int64 num\n')                                   # echo "int64 num" > msg/Num.msg
    for name in ('package.xml', 'CMakeLists.txt'):
        shutil.copy2(os.path.join(REFERENCE, name), os.path.join(pkg, name))
    for d in ('scripts', 'msg', 'launch'):
        for name in os.listdir(os.path.join(REFERENCE, d)):
            shutil.copy2(os.path.join(REFERENCE, d, name), os.path.join(pkg, d, name))
    build = S.catkin_build(ws)
    return dict(ws=ws, pkg=pkg, env=S.overlay_env(ws), created=created, create_out=out,
                generated_xml=generated_xml, build=build)


def test_catkin_create_pkg_creates_package(workspace):
    assert workspace['created'] == ['CMakeLists.txt', 'package.xml', 'src']
    assert 'Successfully created files' in workspace['create_out']
    xml = workspace['generated_xml']
    assert '<name>my_super_robot_controller</name>' in xml
    assert '<build_depend>rospy</build_depend>' in xml and '<exec_depend>std_msgs</exec_depend>' in xml


def test_package_builds_and_is_found(workspace):
    assert 'Failed: No packages failed' in workspace['build'] or 'succeeded' in workspace['build']
    env = workspace['env']
    assert S.sh(['rospack', 'find', PKG], env).strip() == workspace['pkg']
    deps = S.sh(['rospack', 'depends1', PKG], env).split()
    for d in ('rospy', 'std_msgs', 'message_runtime'):
        assert d in deps, deps
    assert 'roscpp' in S.sh(['rospack', 'depends', PKG], env).split()     # indirect, via rospy


def test_rosmsg_show_custom_messages(workspace):
    env = workspace['env']
    num = S.sh(['rosmsg', 'show', PKG + '/Num'], env).split('\n')
    assert [l for l in num if l] == ['string first_name', 'string last_name', 'uint8 age',
                                     'uint32 score']
    pos = S.sh(['rosmsg', 'show', PKG + '/Position2d'], env).split('\n')
    assert [l for l in pos if l] == ['float32 x', 'float32 y']
    assert PKG + '/Position2d' in S.sh(['rosmsg', 'package', PKG], env).split()
    # a message type that does not exist: an error, non-zero exit, no traceback
    rc, out, err = S.sh_rc(['rosmsg', 'show', PKG + '/NoSuchMsg'], env)
    assert rc != 0 and 'Traceback' not in err


def test_pure_logic_of_the_nodes(workspace, monkeypatch):
    """The decision functions of the scripts, without a master."""
    monkeypatch.syspath_prepend(os.path.join(workspace['ws'], 'devel', 'lib', 'python3',
                                             'dist-packages'))
    for name in list(sys.modules):
        if name.split('.')[0] == PKG:
            monkeypatch.delitem(sys.modules, name)
    super_node = _load_script(os.path.join(REFERENCE, 'scripts', 'super_node.py'), 't2_super')
    assert super_node.compute_cmd(CENTRE) == (2.0, 0.0)
    assert super_node.compute_cmd(9.5) == (1.0, 1.4)
    assert super_node.compute_cmd(1.0) == (1.0, 1.4)
    ctl = _load_script(os.path.join(REFERENCE, 'scripts', 'controller.py'), 't2_controller')
    assert ctl.compute_cmd(CENTRE, CENTRE, 2.0) == (2.0, 0.0)
    assert ctl.compute_cmd(CENTRE, 10.0, 2.0) == (1.0, 1.4)     # near the top wall too
    assert ctl.compute_cmd(0.5, CENTRE, 3.0) == (1.5, 1.4)
    assert ctl.check_speed('1.5') == 1.5
    for bad in (-1, 0, 'fast', float('nan'), None):
        with pytest.raises(ValueError, match='~speed'):
            ctl.check_speed(bad)
    pos = _load_script(os.path.join(REFERENCE, 'scripts', 'position2d_node.py'), 't2_pos')
    from turtlesim.msg import Pose
    p = pos.to_position2d(Pose(x=1.25, y=3.5, theta=0.3))
    assert (p.x, p.y) == (1.25, 3.5) and type(p).__name__ == 'Position2d'


def _load_script(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# A child process that listens to a pose topic and a Position2d topic for a while and prints
# what it saw as one YAML line: every position2d must be the (x, y) of a pose published.
PROBE = r'''
import json, sys, time, rospy
from turtlesim.msg import Pose
from my_super_robot_controller.msg import Position2d
pose_topic, pos_topic, n, motion = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4] == 'motion'
rospy.init_node('probe', anonymous=True)
poses, positions = [], []
rospy.Subscriber(pose_topic, Pose, lambda m: poses.append((m.x, m.y, m.theta, m.linear_velocity, m.angular_velocity)))
# each position with the number of poses received before it: a position that arrives before
# this probe's pose subscription is connected has no pose to be compared with
rospy.Subscriber(pos_topic, Position2d, lambda m: positions.append((m.x, m.y, len(poses))))

def drove_and_turned():
    # the controller may start well after turtlesim on a loaded machine: wait for what it does
    # (straight to the wall, a turn there), not for a fixed number of poses
    ps = list(poses)
    return (any(p[0] > 9.0 for p in ps) and any(abs(p[4] - 1.4) < 1e-3 for p in ps)
            and any(p[4] == 0.0 and p[3] == 2.0 for p in ps))

deadline = time.time() + 120   # a bound on a broken run, not a speed requirement
while ((len(positions) < n or len(poses) < n or (motion and not drove_and_turned()))
       and time.time() < deadline and not rospy.is_shutdown()):
    time.sleep(0.05)
seen = set((p[0], p[1]) for p in poses)
# what position2d_node did, judged by causality, not by when this probe saw it: it republishes
# every pose it receives, in order, so each position is a pose turtlesim published. This probe
# receives those poses in the same order but may miss some (turtlesim's publisher queue is 1 on
# a loaded machine) or get them later than the positions. Positions are compared up to the
# last one whose pose this probe received itself (exact): every earlier position came from a
# pose published no later, which this probe has therefore received or missed for good. A
# missed pose lies on the turtle's path between the two received around it: on the chord of
# that piece of path, within half its length (an arc's sagitta is never longer) + 2 cm.
end = time.time() + 10      # the poses of the last positions, if they are late
while time.time() < end and not rospy.is_shutdown():
    seen = set((p[0], p[1]) for p in poses)
    if positions and (positions[-1][0], positions[-1][1]) in seen:
        break
    time.sleep(0.05)
last = max([i for i, q in enumerate(positions) if (q[0], q[1]) in seen] or [-1])
compared = [q for q in positions[:last + 1] if q[2] >= 5]
path = [(p[0], p[1]) for p in poses]
def on_path(q):
    for (x0, y0), (x1, y1) in zip(path, path[1:]):
        dx, dy = x1 - x0, y1 - y0
        ln2 = dx * dx + dy * dy
        t = 0.0 if ln2 == 0 else max(0.0, min(1.0, ((q[0] - x0) * dx + (q[1] - y0) * dy) / ln2))
        d = ((q[0] - x0 - t * dx) ** 2 + (q[1] - y0 - t * dy) ** 2) ** 0.5
        if d <= 0.02 + 0.5 * ln2 ** 0.5:
            return True
    return len(path) == 1 and abs(q[0] - path[0][0]) < 0.02 and abs(q[1] - path[0][1]) < 0.02
matched = sum(1 for q in compared if (q[0], q[1]) in seen or on_path(q))
exact = sum(1 for q in compared if (q[0], q[1]) in seen)
print(json.dumps({'poses': len(poses), 'positions': len(positions), 'matched': matched, 'exact': exact,
       'compared': len(compared),
       'x_max': max([p[0] for p in poses] or [0]), 'x_min': min([p[0] for p in poses] or [0]),
       'turning': sum(1 for p in poses if abs(p[4] - 1.4) < 1e-3 and p[3] == 1.0),
       'straight': sum(1 for p in poses if p[4] == 0.0 and p[3] == 2.0),
       'turn_x_ok': all(p[0] > 8.9 or p[0] < 2.1 for p in poses if abs(p[4] - 1.4) < 1e-3)}))
'''


def _probe(env, pose_topic, pos_topic, n, motion=False):
    return S.run_probe(PROBE.replace("sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4] == 'motion'",
                                     '%r, %r, %d, %r' % (pose_topic, pos_topic, n, motion)), env,
                       timeout=180)


def test_super_node_with_rosrun(workspace, roscore, xvfb, tmp_path):
    """Section 3.2: rosrun turtlesim turtlesim_node + rosrun ... super_node.py."""
    env = S.with_master(workspace['env'], roscore, xvfb)
    sim = S.launch(['rosrun', 'turtlesim', 'turtlesim_node'], env, tmp_path / 'sim.log')
    node = S.launch(['rosrun', PKG, 'super_node.py'], env, tmp_path / 'node.log')
    try:
        S.wait_output(node, 'Node started...')
        S.wait_output(node, 'Super node sending new msg')
        p0 = S.wait_topic('/turtle1/pose', env, proc=sim)
        wait_for(lambda: S.echo_once('/turtle1/pose', env)['x'] > 9.0, 60, 0.2,
                 'the turtle to reach x > 9 (2 m/s from the centre)')
        p1 = S.echo_once('/turtle1/pose', env)
        assert p1['linear_velocity'] in (1.0, 2.0)
        assert (p1['x'], p1['y']) != (p0['x'], p0['y'])
        assert '/turtle_super_node' in S.sh(['rosnode', 'list'], env).split()
    finally:
        S.stop_all(node, sim)


def test_my_setup_launch(workspace, roscore, xvfb, tmp_path):
    """Sections 3.3.3 and 3.4.1: roslaunch my_setup.launch starts turtlesim, the controller and
    the position2d republisher; the turtle drives and turns near the walls."""
    env = S.with_master(workspace['env'], roscore, xvfb)
    lp = S.launch(['roslaunch', PKG, 'my_setup.launch'], env, tmp_path / 'launch.log')
    try:
        S.wait_topic('/position2d', env, proc=lp)
        nodes = S.sh(['rosnode', 'list'], env).split()
        for n in ('/sim', '/my_super_robot_controller', '/position2d_node'):
            assert n in nodes, nodes
        assert S.sh(['rostopic', 'type', '/position2d'], env).strip() == PKG + '/Position2d'
        seen = _probe(env, '/turtle1/pose', '/position2d', 300, motion=True)   # >= 5 s at 62.5 Hz
        assert seen['positions'] >= 300 and seen['poses'] >= 300, seen
        assert seen['matched'] == seen['compared'] >= 200, seen  # position2d carries pose x, y
        assert seen['exact'] >= seen['compared'] // 2, seen      # (most of them seen exactly)
        assert seen['straight'] > 0 and seen['turning'] > 0, seen  # both branches of the law
        assert seen['turn_x_ok'], seen
        assert seen['x_max'] > 9.0, seen
        pos = S.echo_once('/position2d', env)
        assert 0.0 <= pos['x'] <= FIELD and 0.0 <= pos['y'] <= FIELD
        png = str(tmp_path / 'my_setup.png')
        screenshot(xvfb.display, png)
        if os.environ.get('COURSE_SHOTS_DIR'):
            shutil.copy(png, os.path.join(os.environ['COURSE_SHOTS_DIR'], 'task2_my_setup.png'))
        assert S.unique_colours(png) > 5
        assert 'Super node sending new msg' in lp.output()
    finally:
        lp.stop()


def test_two_controllers_in_namespaces(workspace, roscore, xvfb, tmp_path):
    """Section 3.4: <group ns="ns1"> / <group ns="ns2">, each a turtlesim with its controller."""
    env = S.with_master(workspace['env'], roscore, xvfb)
    lp = S.launch(['roslaunch', PKG, 'my_setup_ns.launch'], env, tmp_path / 'launch.log')
    try:
        S.wait_topic('/ns1/position2d', env, proc=lp)
        S.wait_topic('/ns2/position2d', env, proc=lp)
        nodes = S.sh(['rosnode', 'list'], env).split()
        for n in ('/ns1/sim', '/ns1/controller', '/ns2/sim', '/ns2/controller'):
            assert n in nodes, nodes
        topics = S.sh(['rostopic', 'list'], env).split()
        for ns in ('/ns1', '/ns2'):
            for t in ('/turtle1/pose', '/turtle1/cmd_vel', '/position2d'):
                assert ns + t in topics, topics
        assert '/turtle1/pose' not in topics and '/position2d' not in topics
        for ns, speed in (('/ns1', 2.0), ('/ns2', 1.0)):     # ns2 sets ~speed 1.0
            seen = _probe(env, ns + '/turtle1/pose', ns + '/position2d', 100)
            assert seen['matched'] == seen['compared'] >= 50 and seen['positions'] >= 100, (ns, seen)
            first = S.echo_once(ns + '/turtle1/pose', env)
            moved = wait_for(lambda: _moved(S.echo_once(ns + '/turtle1/pose', env), first, 0.5),
                             60, 0.2, 'the %s turtle to move' % ns)
            assert moved['linear_velocity'] in (speed, speed / 2), (ns, moved)
        assert 'driving turtle /ns1/turtle1 at 2.00 m/s' in lp.output()
        assert 'driving turtle /ns2/turtle1 at 1.00 m/s' in lp.output()
    finally:
        lp.stop()


def _moved(pose, first, dist):
    return pose if math.hypot(pose['x'] - first['x'], pose['y'] - first['y']) > dist else None


def _off_arc(pose, start, radius):
    """(distance from, heading error against) the left-turning circle of `radius` that a turtle
    starting at pose `start` follows under a constant command."""
    cx = start['x'] - radius * math.sin(start['theta'])
    cy = start['y'] + radius * math.cos(start['theta'])
    off = abs(math.hypot(pose['x'] - cx, pose['y'] - cy) - radius)
    tangent = math.atan2(pose['y'] - cy, pose['x'] - cx) + math.pi / 2
    return off, abs(math.remainder(pose['theta'] - tangent, 2 * math.pi))


def test_mimic_launch(workspace, roscore, xvfb, tmp_path):
    """The textbook's launch example: turtlesim2's turtle repeats turtlesim1's motion."""
    env = S.with_master(workspace['env'], roscore, xvfb)
    lp = S.launch(['roslaunch', PKG, 'mimic.launch'], env, tmp_path / 'launch.log')
    drive = None
    try:
        S.wait_topic('/turtlesim1/turtle1/pose', env, proc=lp)
        S.wait_topic('/turtlesim2/turtle1/pose', env, proc=lp)
        nodes = S.sh(['rosnode', 'list'], env).split()
        for n in ('/turtlesim1/sim', '/turtlesim2/sim', '/mimic'):
            assert n in nodes, nodes
        info = S.sh(['rosnode', 'info', '/mimic'], env)
        assert '/turtlesim1/turtle1/pose' in info and '/turtlesim2/turtle1/cmd_vel' in info, info
        start = S.echo_once('/turtlesim2/turtle1/pose', env)
        drive = S.launch(['rostopic', 'pub', '-r', '5', '/turtlesim1/turtle1/cmd_vel',
                          'geometry_msgs/Twist', '{linear: {x: 1.5}, angular: {z: 0.9}}'],
                         env, tmp_path / 'pub.log')
        wait_for(lambda: _moved(S.echo_once('/turtlesim2/turtle1/pose', env), start, 1.5),
                 60, 0.2, 'turtle 2 to follow turtle 1')
        drive.stop()
        drive = None

        def both_stopped():
            a = S.echo_once('/turtlesim1/turtle1/pose', env)
            b = S.echo_once('/turtlesim2/turtle1/pose', env)
            return (a, b) if a['linear_velocity'] == 0.0 and b['linear_velocity'] == 0.0 else None
        a, b = wait_for(both_stopped, 60, 0.2, 'both turtles to stop')
        # turtle 2 integrates turtle 1's velocities as they arrive; on a loaded machine some
        # arrive late (turtlesim zeroes a command older than 1 s of wall time, as the original),
        # so it may lag turtle 1 along the way: both must be on the arc that the command
        # (1.5 m/s, 0.9 rad/s) draws from their common start pose, heading along it
        for who, pose in (('turtle 1', a), ('turtle 2', b)):
            off, heading = _off_arc(pose, start, 1.5 / 0.9)
            assert off < 0.3, '%s is %.2f m off the arc driven from %s: %s' % (who, off, start, pose)
            assert heading < 0.3, '%s heads %.2f rad off the arc: %s' % (who, heading, pose)
        # (how far turtle 2 went was checked while it drove: a chord of the arc longer than 1.5 m;
        # the chord at the stop says nothing — a loaded machine stops the drive late, and one lap
        # of the circle takes 7 s)
    finally:
        S.stop_all(drive, lp)


def test_controller_rejects_bad_speed(workspace, roscore, tmp_path):
    env = S.with_master(workspace['env'], roscore)
    rc, out, err = S.sh_rc(['rosrun', PKG, 'controller.py', '_speed:=-1'], env, timeout=60)
    assert rc != 0
    assert 'parameter ~speed must be a positive number' in err, (out, err)
    assert 'Traceback' not in err + out
