"""The diploma's robot_config.launch with its defaults — rosserial, rplidar, Madgwick's filter,
the EKF, the Diffbot, the controllers, robot_state_publisher — on emulated devices: the Arduino
Mega running space_scanner_base in simavr (firmware/simulate's pty as `port`) and the RPLidar A1
emulator (rplidar_ros' rplidar_emulator as `lidar_port`). Every stage of the chain delivers:
the scan, the filtered IMU, the controller's and the EKF's odometry while driving, and
robot_state_publisher moves all four wheels (the Diffbot's joint names are the URDF's)."""
import os
import re
import subprocess
import sys

import yaml

from course_testing import Proc, wait_for

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), *['..'] * 5))
sys.path.insert(0, os.path.join(REPO, 'firmware', 'hil'))
import harness  # noqa: E402

WHEEL_JOINTS = ['wheel_%d_joint' % i for i in range(4)]
WHEEL_LINKS = {'left_front_wheel', 'right_front_wheel', 'left_rear_wheel', 'right_rear_wheel'}
DIPLOMA_NODES = {'/diffbot', '/controller_spawner', '/rob_st_pub', '/rplidarNode', '/ImuFilterNodelet',
                 '/ekf_loc_node', '/serial_node'}


def echo(env, topic, n=1, timeout=120, launch=None):
    try:
        p = subprocess.run(['rostopic', 'echo', '-n', str(n), topic], env=env, capture_output=True,
                           text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise AssertionError('no %d message(s) on %s within %d s; launch log:\n%s'
                             % (n, topic, timeout, launch.output()[-4000:] if launch else ''))
    assert p.returncode == 0, p.stderr
    return p.stdout


def messages(text):
    return [yaml.safe_load(m) for m in text.split('\n---\n') if m.strip()]


def floats(text, key):
    return [float(v) for v in re.findall(r'^\s*%s: ([-0-9.e+]+)$' % key, text, re.M)]


def test_robot_config_defaults_on_emulated_devices(roscore, tmp_path):
    env = roscore.env
    elf = harness.build('space_scanner_base', env=env)
    lidar_port = str(tmp_path / 'ttyRPLIDAR')
    with harness.Simulation(elf) as sim:
        lidar = Proc(['rosrun', 'rplidar_ros', 'rplidar_emulator', '_port:=' + lidar_port], env=env,
                     log=str(tmp_path / 'emulator.log'))
        launch = pub = None
        try:
            wait_for(lambda: os.path.exists(lidar_port), 60, what='the emulator\'s pty %s' % lidar_port)
            launch = Proc(['roslaunch', 'space_scanner_hw', 'robot_config.launch', 'port:=' + sim.pty,
                           'lidar_port:=' + lidar_port], env=env, log=str(tmp_path / 'launch.log'))
            wait_for(lambda: DIPLOMA_NODES <= set(subprocess.run(
                ['rosnode', 'list'], env=env, capture_output=True, text=True, timeout=60).stdout.split()),
                120, interval=1.0,
                what='the diploma\'s nodes %s; launch log:\n%s' % (sorted(DIPLOMA_NODES), launch.output()[-3000:]))

            scan = echo(env, '/scan', launch=launch)
            assert 'frame_id: "laser"' in scan, scan[:500]
            imu = echo(env, '/imu/data', launch=launch)              # Madgwick's output
            assert 'frame_id: "imu_link"' in imu, imu[:500]
            w = floats(imu.split('orientation_covariance')[0], 'w')
            assert w and abs(w[0]) > 0.9, imu[:600]                    # level: close to identity

            js = echo(env, '/joint_states', launch=launch)
            assert yaml.safe_load(js.split('---')[0])['name'] == WHEEL_JOINTS, js

            # drive: cmd_vel -> diff_drive_controller -> Diffbot -> rosserial -> firmware -> encoders
            pub = Proc(['rostopic', 'pub', '-r', '10', '/diffbot_controller/cmd_vel', 'geometry_msgs/Twist',
                        '{linear: {x: 0.2}}'], env=env)
            sim.wait_event('motor', count=30, timeout=240)         # 3 s of the wheels turning
            odom = messages(echo(env, '/diffbot_controller/odom', n=3, launch=launch))
            vx = [m['twist']['twist']['linear']['x'] for m in odom]
            assert abs(sum(vx) / 3 - 0.195) < 0.03, vx               # trunc(0.2 / 0.0325) = 6 rad/s
            # the EKF's odometry/filtered reports the forward motion: three messages in a row (it
            # differentiates the IMU's yaw over the devices' stamps, which a busy machine bunches:
            # a message of a transient is read again, not taken as the answer)
            ekf = []

            def ekf_moving():
                ekf[:] = messages(echo(env, '/odom', n=3, launch=launch))
                assert all(m['child_frame_id'] == 'base_footprint' for m in ekf), ekf[0]
                return all(m['twist']['twist']['linear']['x'] > 0.1 for m in ekf)
            try:
                wait_for(ekf_moving, 120, interval=0.1, what='the EKF\'s /odom moving forward')
            except TimeoutError as e:
                raise AssertionError('%s; the last three: %s' % (e, [m['twist'] for m in ekf]))

            # robot_state_publisher: every wheel's transform (names agree with the Diffbot's)
            seen = set()

            def wheels_seen():
                seen.update(re.findall(r'child_frame_id: "([^"]+)"', echo(env, '/tf', n=5, launch=launch)))
                return WHEEL_LINKS <= seen
            wait_for(wheels_seen, 180, interval=0.5, what='/tf of every wheel, seen %s' % sorted(seen))
        finally:
            if pub:
                pub.stop()
            if launch:
                launch.stop()
            lidar.stop()
