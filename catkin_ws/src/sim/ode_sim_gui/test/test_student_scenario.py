"""Done-when of issue 31 §1, scripted as a student under Xvfb: `roslaunch my_robot_simulation
sim.launch`, the window (pytest-qt, student_scenario.py in a process of its own on this test's
display and roscore) inserts three library models and a box, moves one, deletes one, pauses
and steps 100 steps, saves the world; then the simulator restarted on the saved file has the
same models at the same poses."""
import json
import math
import os
import subprocess
import sys

from course_testing import Proc
from course_testing.gui_check import keep

HERE = os.path.dirname(os.path.abspath(__file__))


def model_poses(env, names):
    """{name: [[x, y, z], [qx, qy, qz, qw]]} from /gazebo/get_model_state (a paused simulator
    publishes no model_states)."""
    out = subprocess.run([sys.executable, '-c', '''
import json, sys, rospy
from gazebo_msgs.srv import GetModelState
rospy.wait_for_service("/gazebo/get_model_state", timeout=120)
get = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
res = {}
for n in sys.argv[1:]:
    r = get(model_name=n, relative_entity_name="world")
    if r.success:
        p = r.pose
        res[n] = [[p.position.x, p.position.y, p.position.z],
                  [p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w]]
print(json.dumps(res))
'''] + list(names), env=env, capture_output=True, text=True, timeout=180)
    assert out.returncode == 0, out.stderr[-2000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


def world_models(env):
    out = subprocess.run([sys.executable, '-c', '''
import json, rospy
from gazebo_msgs.srv import GetWorldProperties
rospy.wait_for_service("/gazebo/get_world_properties", timeout=120)
print(json.dumps(rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)().model_names))
'''], env=env, capture_output=True, text=True, timeout=180)
    assert out.returncode == 0, out.stderr[-2000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_student_builds_a_scene_in_the_window(roscore, screen, tmp_path):
    env = dict(roscore.env, DISPLAY=screen.display, SCENARIO_OUT=str(tmp_path))
    env.pop('QT_QPA_PLATFORM', None)
    sim = Proc(['roslaunch', 'my_robot_simulation', 'sim.launch', 'gui:=false', 'rviz:=false'],
               env=env, log=str(tmp_path / 'sim.log'))
    try:
        run = subprocess.run([sys.executable, '-m', 'pytest', '-q', '-x', '-p', 'no:cacheprovider',
                              '-o', 'qt_api=pyqt5', os.path.join(HERE, 'student_scenario.py')],
                             env=env, capture_output=True, text=True, timeout=800, cwd=HERE)
        (tmp_path / 'scenario.log').write_text(run.stdout + run.stderr)
        for name in ('before.png', 'scene.png'):
            if (tmp_path / name).exists():
                keep(str(tmp_path / name), 'ode_sim_gui_student_' + name)
        assert run.returncode == 0, 'scenario failed (log %s):\n%s' % (
            tmp_path / 'scenario.log', run.stdout[-6000:] + run.stderr[-3000:])
    finally:
        sim.stop()
    exp = json.loads((tmp_path / 'expected.json').read_text())
    # the simulator again, paused, on the saved world: the same models at the same poses
    again = Proc(['roslaunch', 'gazebo_ros', 'empty_world.launch', 'world_name:=' + exp['world'],
                  'paused:=true', 'gui:=false'], env=env, log=str(tmp_path / 'again.log'))
    try:
        names = world_models(env)
        got = model_poses(env, names)
    finally:
        again.stop()
    assert set(names) == set(exp['models']), (sorted(names), sorted(exp['models']))
    for name, (p, q) in exp['models'].items():
        gp, gq = got[name]
        assert math.dist(gp, p) < 2e-3, (name, gp, p)
        dot = abs(sum(a * b for a, b in zip(gq, q)))
        assert dot > 1 - 1e-5, (name, gq, q)
