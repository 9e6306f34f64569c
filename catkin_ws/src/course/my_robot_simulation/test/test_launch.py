"""my_robot_simulation's launch files on a private roscore, headless (gui:=false rviz:=false):
the robot appears in the simulation, drives on /cmd_vel (and by drive.py), a second robot is
spawned at x/y/z in its own namespace, the scene and the several-robots launches load."""
import math

import pytest

from course_testing import Proc
from course_testing import sim_testing as T

HEADLESS = ['gui:=false', 'rviz:=false']


@pytest.fixture
def env(roscore):
    return T.ros_env(roscore)


def launch(env, tmp_path, name, *args):
    return T.roslaunch('my_robot_simulation', name, list(HEADLESS) + list(args), env,
                       tmp_path / (name + '.log'))


def test_sim_launch_drive_and_spawn_a_second_robot(env, tmp_path):
    p = launch(env, tmp_path, 'sim.launch')
    q = None
    try:
        start = T.probe(['model', 'my_robot_model', '--timeout', 60], env, proc=p)['pose']
        assert abs(start['x']) < 0.05 and abs(start['y']) < 0.05 and 0.0 < start['z'] < 0.1, start
        res = T.probe(['drive', 'my_robot_model', '--topic', '/cmd_vel', '--odom', '/odom',
                       '--vx', 0.3, '--seconds', 2.0], env, proc=p)
        b, a = res['before'], res['after']
        dist = math.hypot(a['x'] - b['x'], a['y'] - b['y'])
        assert 0.35 < dist < 0.75, res            # 0.3 m/s for 2 s of simulated time
        assert abs(a['y'] - b['y']) < 0.1 and abs(a['yaw'] - b['yaw']) < 0.15, res
        odom = res['odom']
        assert odom and odom['frame_id'].endswith('odom') and odom['child_frame_id'].endswith('base_link')
        assert odom['pose']['x'] == pytest.approx(a['x'], abs=0.1)
        # turning in place on angular.z
        res = T.probe(['drive', 'my_robot_model', '--wz', 1.0, '--seconds', 1.5], env, proc=p)
        turned = math.remainder(res['after']['yaw'] - res['before']['yaw'], 2 * math.pi)
        assert 0.8 < turned < 2.2, res
        parked = res['after']
        # a second robot at x/y/z, in its own namespace
        q = T.roslaunch('my_robot_simulation', 'spawn_robot.launch',
                        ['robot_name:=robot2', 'x:=1.0', 'y:=1.0', 'z:=0.2'], env, tmp_path / 'spawn.log')
        r2 = T.probe(['model', 'robot2', '--timeout', 60], env, proc=q)['pose']
        assert r2['x'] == pytest.approx(1.0, abs=0.1) and r2['y'] == pytest.approx(1.0, abs=0.1)
        res = T.probe(['drive', 'robot2', '--topic', '/robot2/cmd_vel', '--odom', '/robot2/odom',
                       '--vx', 0.3, '--seconds', 1.5], env, proc=q)
        assert res['after']['x'] - res['before']['x'] > 0.25, res
        assert res['odom'] is not None, 'no odometry on /robot2/odom'
        first = T.probe(['model', 'my_robot_model'], env)['pose']
        assert first['x'] == pytest.approx(parked['x'], abs=0.02), 'robot 1 moved with robot 2'
        assert first['y'] == pytest.approx(parked['y'], abs=0.02), 'robot 1 moved with robot 2'
        rc, out = T.rosrun_out(['rosservice', 'call', '/gazebo/get_model_state',
                                '{model_name: robot2}'], env)
        assert rc == 0 and 'success: True' in out, out
    finally:
        if q is not None:
            q.stop()
        p.stop()


def test_sim_xyz_launch_and_drive_script(env, tmp_path):
    p = launch(env, tmp_path, 'sim_xyz.launch', 'x:=1.0', 'y:=-0.5', 'z:=0.3', 'Y:=1.5708')
    d = None
    try:
        pose = T.probe(['model', 'my_robot_model'], env, proc=p)['pose']
        assert pose['x'] == pytest.approx(1.0, abs=0.05) and pose['y'] == pytest.approx(-0.5, abs=0.05)
        assert pose['yaw'] == pytest.approx(1.5708, abs=0.1)
        d = Proc(['rosrun', 'my_robot_simulation', 'drive.py', '_pattern:=forward', '_speed:=0.3',
                  '_duration:=2.0'], env=env, log=str(tmp_path / 'drive.log'))
        d.popen.wait(90)
        assert d.popen.returncode == 0, d.output()
        after = T.probe(['model', 'my_robot_model'], env, proc=p)['pose']
        # facing +y: driving forward moves the robot along +y
        assert after['y'] - pose['y'] > 0.3 and abs(after['x'] - pose['x']) < 0.15, (pose, after)
        assert after['z'] < 0.1, 'the robot did not fall onto the ground: %s' % after
    finally:
        if d is not None:
            d.stop()
        p.stop()


def test_scene_launch_loads_the_library_objects(env, tmp_path):
    p = launch(env, tmp_path, 'scene.launch')
    try:
        T.probe(['model', 'my_robot_model'], env, proc=p)
        for name in ('cone_ahead', 'table', 'bookshelf', 'crate'):
            T.probe(['model', name, '--timeout', 20], env, proc=p)
        # the simulator advertises its scene markers once someone subscribes (RViz's scene
        # display does; ode_sim's README): subscribe as RViz would, with the type known
        code, out = T.rosrun_out(
            ['/usr/bin/python3', '-c',
             'import rospy; from visualization_msgs.msg import MarkerArray; '
             'rospy.init_node("scene_check", anonymous=True); '
             'm = rospy.wait_for_message("/gazebo/scene_markers", MarkerArray, timeout=60); '
             'print(sorted({k.ns for k in m.markers}))'], env, timeout=120)
        assert code == 0, out + p.output()[-2000:]
        for name in ('cone_ahead', 'table', 'bookshelf', 'crate'):
            assert 'ode_sim/' + name in out, out
    finally:
        p.stop()


def test_several_robots_launch(env, tmp_path):
    p = launch(env, tmp_path, 'several_robots.launch')
    try:
        poses = {n: T.probe(['model', n], env, proc=p)['pose'] for n in ('robot1', 'robot2', 'robot3')}
        assert poses['robot2']['y'] == pytest.approx(1.0, abs=0.1)
        assert poses['robot3']['x'] == pytest.approx(-1.0, abs=0.1)
        res = T.probe(['drive', 'robot3', '--topic', '/robot3/cmd_vel', '--vx', 0.3, '--seconds', 1.5],
                      env, proc=p)
        assert res['after']['y'] - res['before']['y'] > 0.25, res       # robot3 faces +y
        assert T.probe(['model', 'robot1'], env)['pose']['x'] == pytest.approx(poses['robot1']['x'], abs=0.05)
        odom = T.probe(['topic', '/robot2/odom'], env, proc=p)
        assert odom['frame_id'] == 'robot2/odom' and odom['child_frame_id'] == 'robot2/base_link'
    finally:
        p.stop()
