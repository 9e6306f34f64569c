"""robot_sim_camera.launch headless on a private roscore: the textbook's /diff_drive_robot/laser and
/diff_drive_robot/camera1/image_raw arrive
with the configured sizes, the lidar sees the scene's objects, sensor_data_proc.py publishes
the Canny edges of the camera image."""
import pytest

from course_testing import sim_testing as T


def test_robot_sim_camera_launch(roscore, tmp_path):
    env = T.ros_env(roscore)
    p = T.roslaunch('my_robot_simulation_sensors', 'robot_sim_camera.launch',
                    ['gui:=false', 'rviz:=false'], env, tmp_path / 'launch.log')
    try:
        T.probe(['model', 'diff_drive_robot1'], env, proc=p)
        scan = T.probe(['topic', '/diff_drive_robot/laser'], env, proc=p)
        assert scan['type'] == 'sensor_msgs/LaserScan' and scan['frame_id'] == 'lidar'
        assert scan['samples'] == 720
        assert scan['angle_min'] == pytest.approx(-0.785, abs=1e-3)
        assert scan['range_min'] == pytest.approx(0.03) and scan['range_max'] == pytest.approx(3.0)
        # the traffic cone of my_scene.world stands 1.5 m ahead
        assert scan['finite'] > 0 and scan['nearest'] < 1.6, scan
        img = T.probe(['topic', '/diff_drive_robot/camera1/image_raw', '--save', tmp_path / 'camera.png'], env, proc=p)
        assert (img['width'], img['height'], img['encoding']) == (600, 400, 'rgb8'), img
        assert img['frame_id'] == 'camera' and img['bytes'] == 600 * 400 * 3
        info = T.probe(['topic', '/diff_drive_robot/camera1/camera_info'], env, proc=p)
        assert (info['width'], info['height']) == (600, 400)
        assert 40 < img['mean'] < 230, 'the camera image is blank: %s' % img
        edges = T.probe(['topic', '/sensor_data_proc/edges', '--save', tmp_path / 'edges.png'], env, proc=p)
        assert (edges['width'], edges['height'], edges['encoding']) == (600, 400, 'mono8'), edges
        # the cone, the crate and the horizon give edges; a blank image gives none
        assert 200 < edges['nonzero'] < 0.2 * 600 * 400, 'edges in %s: %s' % (tmp_path / 'camera.png', edges)
        assert 'image 600x400' in p.output()
    finally:
        p.stop()
