"""jacksonbot_sim.launch headless on a private roscore: the robot stands in its room, drives on
/cmd_vel, and every sensor topic of the tutorial delivers messages of the configured shape."""
import math

import pytest

from course_testing import sim_testing as T


def test_jacksonbot_sim_launch(roscore, tmp_path):
    env = T.ros_env(roscore)
    p = T.roslaunch('jacksonbot_simulation', 'jacksonbot_sim.launch', ['gui:=false', 'rviz:=false'],
                    env, tmp_path / 'launch.log')
    try:
        pose = T.probe(['model', 'jacksonbot'], env, proc=p)['pose']
        assert abs(pose['x']) < 0.05 and abs(pose['z']) < 0.05
        scan = T.probe(['topic', '/scan'], env, proc=p)
        assert scan['samples'] == 360 and scan['frame_id'] == 'laser_link'
        # the room's walls are 2 to 3.2 m away all around
        assert scan['finite'] > 300 and 0.5 < scan['nearest'] < 2.2, scan
        imu = [T.probe(['topic', '/imu'], env, proc=p) for _ in range(2)]
        assert imu[0]['frame_id'] == 'imu_link'
        assert imu[0]['linear_acceleration'][2] == pytest.approx(9.8, abs=0.5)
        assert imu[0]['angular_velocity'] != imu[1]['angular_velocity'], 'no noise on /imu'
        img = T.probe(['topic', '/camera_sensor/image_raw'], env, proc=p)
        assert (img['width'], img['height']) == (640, 480)
        depth = T.probe(['topic', '/camera_sensor/depth/image_raw'], env, proc=p)
        assert (depth['width'], depth['height'], depth['encoding']) == (640, 480, '32FC1')
        cloud = T.probe(['topic', '/camera_sensor/points'], env, proc=p)
        assert cloud['frame_id'] == 'camera_optical_link' and {'x', 'y', 'z'} <= set(cloud['fields'])
        odom = T.probe(['topic', '/odom'], env, proc=p)
        assert odom['frame_id'] == 'odom' and odom['child_frame_id'] == 'base_footprint'
        js = T.probe(['topic', '/joint_states'], env, proc=p)
        assert js['type'] == 'sensor_msgs/JointState'
        res = T.probe(['drive', 'jacksonbot', '--vx', 0.2, '--seconds', 2.0], env, proc=p)
        moved = math.hypot(res['after']['x'] - res['before']['x'], res['after']['y'] - res['before']['y'])
        assert 0.25 < moved < 0.5, res
    finally:
        p.stop()
