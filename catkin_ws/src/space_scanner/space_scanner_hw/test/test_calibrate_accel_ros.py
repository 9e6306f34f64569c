"""calibrate_accel through ROS: `rosrun space_scanner_hw calibrate_accel` fits a known ellipsoid
from sensor_msgs/Imu messages in a bag file and from the live imu/data_raw topic; the header it
writes, built into the firmware (space_scanner_base on the emulated Mega), makes imu/data_raw
report A^-1 (M - b) of the MPU6050's reading."""
import os
import re
import shutil
import subprocess
import sys

import numpy as np

from course_testing import Proc, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, *['..'] * 5))
sys.path.insert(0, os.path.join(REPO, 'firmware', 'hil'))
sys.path.insert(0, HERE)
import harness  # noqa: E402
from test_accel_calibration import A_TRUE, B_TRUE, readings  # noqa: E402

from space_scanner_hw import accel_calibration as ac  # noqa: E402


def imu_msg(acc, stamp=None):
    from sensor_msgs.msg import Imu
    m = Imu()
    m.header.frame_id = 'imu_link'
    if stamp is not None:
        m.header.stamp = stamp
    m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z = acc
    m.orientation_covariance[0] = -1
    return m


def check_header(path, a=A_TRUE, b=B_TRUE):
    with open(path) as f:
        a_inv, off = ac.parse_header(f.read())
    assert np.allclose(np.linalg.inv(a_inv), a, atol=3e-3), a_inv
    assert np.allclose(off, b, atol=6e-3), off


def test_from_a_bag(tmp_path):
    import rosbag
    import rospy
    samples, _ = readings(n=300, seed=7)
    bag_path = str(tmp_path / 'imu.bag')
    with rosbag.Bag(bag_path, 'w') as bag:
        for k, acc in enumerate(samples):
            t = rospy.Time(100 + k * 0.1)
            bag.write('/imu/data_raw', imu_msg(acc, t), t)
            bag.write('/other', imu_msg((0.0, 0.0, 0.0), t), t)      # not read
    out = tmp_path / 'accel_calibration.h'
    r = subprocess.run(['rosrun', 'space_scanner_hw', 'calibrate_accel', '--bag', bag_path, '-o', str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert '300 samples' in r.stderr, r.stderr
    check_header(out)
    # a topic the bag does not have: one clear line
    r = subprocess.run(['rosrun', 'space_scanner_hw', 'calibrate_accel', '--bag', bag_path, '--topic', 'imu/nothing'],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 1 and 'has no messages on imu/nothing' in r.stderr, r.stderr


PUBLISHER = r'''
import sys, numpy as np, rospy
from sensor_msgs.msg import Imu
sys.path.insert(0, sys.argv[1])
from test_calibrate_accel_ros import imu_msg
from test_accel_calibration import readings
rospy.init_node('imu_player')
pub = rospy.Publisher('imu/data_raw', Imu, queue_size=1000)
samples, _ = readings(n=150, seed=11)
k = 0
while not rospy.is_shutdown():        # the same 150 orientations, over and over
    pub.publish(imu_msg(samples[k % len(samples)]))
    k += 1
    rospy.rostime.wallsleep(0.005)
'''


def test_from_the_live_topic(roscore, tmp_path):
    player = Proc(['/usr/bin/python3', '-c', PUBLISHER, HERE], env=roscore.env, log=str(tmp_path / 'player.log'))
    try:
        out = tmp_path / 'accel_calibration.h'
        r = subprocess.run(['rosrun', 'space_scanner_hw', 'calibrate_accel', '--live', '-n', '400', '-o', str(out)],
                           capture_output=True, text=True, timeout=300, env=roscore.env)
        assert r.returncode == 0, r.stderr + player.output()[-2000:]
        assert '400 samples' in r.stderr and '/imu/data_raw' in r.stderr, r.stderr
        check_header(out)
    finally:
        player.stop()


def test_the_firmware_applies_the_header(roscore, tmp_path):
    """The fitted header in the sketch: the emulated MPU6050 reads 1 g on z (M = (0, 0, g))
    and imu/data_raw must say A^-1 (M - b)."""
    samples, _ = readings(n=300, noise=0.0, seed=5)
    a, b = ac.fit_ellipsoid(samples)
    a_inv = np.linalg.inv(a)
    sketch = tmp_path / 'space_scanner_base'
    shutil.copytree(os.path.join(REPO, 'firmware', 'sketches', 'space_scanner_base'), str(sketch))
    (sketch / 'accel_calibration.h').write_text(ac.header_text(a_inv, b, 'test'))
    p = subprocess.run([os.path.join(REPO, 'firmware', 'build'), str(sketch), '--out', str(tmp_path / 'build')],
                       capture_output=True, text=True, timeout=900, env=roscore.env)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    elf = p.stdout.strip().splitlines()[-1]
    want = a_inv @ (np.array([0.0, 0.0, ac.G]) - b)
    with harness.Simulation(elf) as sim:
        node = Proc(['rosrun', 'rosserial_python', 'serial_node.py', sim.pty], env=roscore.env,
                    log=str(tmp_path / 'serial_node.log'))
        try:
            wait_for(lambda: 'imu/data_raw' in node.output(), 120,
                     what='serial_node setting up imu/data_raw:\n%s' % node.output()[-2000:])
            out = subprocess.run(['rostopic', 'echo', '-n', '2', '/imu/data_raw/linear_acceleration'],
                                 capture_output=True, text=True, timeout=120, env=roscore.env).stdout
        finally:
            node.stop()
    got = [float(v) for v in re.findall(r'^[xyz]: ([-0-9.e]+)$', out, re.M)][-3:]
    assert len(got) == 3, out
    assert np.allclose(got, want, atol=1e-3), (got, want)
    assert not np.allclose(got, [0.0, 0.0, ac.G], atol=0.05)       # the calibration changed it
