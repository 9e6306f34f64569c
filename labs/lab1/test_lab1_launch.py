"""Lab 1's launch files as a student starts them: the starter's start.launch runs its five
nodes; the reference's lab1.launch publishes the variant's result on result_<ISU>."""
import os
import subprocess

import pytest

from course_testing import Proc, RosCore, wait_for
from grading.workspace import build_overlay, course_env

LAB = os.path.dirname(os.path.abspath(__file__))


def _nodes(env):
    r = subprocess.run(['rosnode', 'list'], env=env, capture_output=True, text=True, timeout=30)
    return set(r.stdout.split()) if r.returncode == 0 else set()


@pytest.fixture
def master(tmp_path):
    core = RosCore(log_dir=str(tmp_path / 'ros_log')).start()
    try:
        yield core
    finally:
        core.stop()


def _overlay(source, tmp_path, master):
    env = build_overlay(os.path.join(LAB, source, 'my_robot_controller'), str(tmp_path / 'ws'), course_env())
    env.update(ROS_MASTER_URI=master.uri, ROS_IP='127.0.0.1', ROS_LOG_DIR=master.log_dir)
    return env


def test_starter_start_launch_runs_five_nodes(tmp_path, master):
    env = _overlay('starter', tmp_path, master)
    with Proc(['roslaunch', 'my_robot_controller', 'start.launch'], env=env, log=str(tmp_path / 'launch.log')):
        want = {'/node%d' % i for i in range(1, 6)}
        wait_for(lambda: want <= _nodes(env), 60, 0.5, 'the starter nodes')


def test_reference_lab1_launch_publishes_result(tmp_path, master):
    env = _overlay('reference', tmp_path, master)
    isu = '123453'    # variant 3: node3 computes node1 * node2
    with Proc(['roslaunch', 'my_robot_controller', 'lab1.launch', 'isu:=' + isu], env=env,
              log=str(tmp_path / 'launch.log')) as launch:
        r = subprocess.run(['rostopic', 'echo', '-n', '1', '/result_' + isu], env=env, capture_output=True,
                           text=True, timeout=60)
        assert r.returncode == 0 and 'data:' in r.stdout, launch.output()[-2000:]
        assert {'/node1', '/node2', '/node3'} <= _nodes(env)
