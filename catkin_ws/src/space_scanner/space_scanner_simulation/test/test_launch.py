"""The diploma's simulation.launch headless on a private roscore (gui:=false rviz:=false
teleop:=false drive:=skid_steer; drive:=ros_control, the default, is drive.test): the robot
dropped from 0.85 m lands on its wheels in the office, the RPLidar scan arrives, the skid-steer
drive moves it on /cmd_vel."""
import math

import pytest

from course_testing import sim_testing as T


def test_simulation_launch(roscore, tmp_path):
    env = T.ros_env(roscore)
    p = T.roslaunch('space_scanner_simulation', 'simulation.launch',
                    ['gui:=false', 'rviz:=false', 'teleop:=false', 'drive:=skid_steer'], env,
                    tmp_path / 'launch.log')
    try:
        T.probe(['model', 'robot'], env, proc=p)
        scan = T.probe(['topic', '/scan', '--skip', 2], env, proc=p)      # after the landing
        assert scan['samples'] == 360 and scan['frame_id'] == 'laser'
        assert scan['range_min'] == pytest.approx(0.15) and scan['range_max'] == pytest.approx(12.0)
        assert scan['finite'] > 300, 'the office walls should surround the robot: %s' % scan
        pose = T.probe(['model', 'robot'], env, proc=p)['pose']
        assert pose['z'] < 0.05, 'the robot did not land: %s' % pose
        res = T.probe(['drive', 'robot', '--vx', 0.2, '--seconds', 2.0, '--odom', '/odom'], env, proc=p)
        moved = math.hypot(res['after']['x'] - res['before']['x'], res['after']['y'] - res['before']['y'])
        assert moved > 0.15, res
        assert res['odom']['child_frame_id'] == 'base_footprint'
        cam = T.probe(['topic', '/camera/image_raw'], env, proc=p)
        assert (cam['width'], cam['height']) == (640, 480)
        imu = T.probe(['topic', '/imu/data_raw'], env, proc=p)
        assert imu['frame_id'] == 'imu_link'
    finally:
        p.stop()
