"""The robot with sensors (my_robot_simulation/diff_drive_robot/urdf/diff_drive_robot.xacro, where
the textbook's launch file loads it): expands, passes check_urdf and the simulator checks, carries
the camera and lidar sensors with the textbook's plugin names and values and the diff drive of
practical work 4."""
import os

import pytest

from my_robot_model import model_check as mc

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODEL = os.path.join(SRC, 'my_robot_simulation', 'diff_drive_robot', 'urdf', 'diff_drive_robot.xacro')


@pytest.fixture(scope='module')
def model():
    return mc.checked_model(MODEL,
                            root_frames=())


def sensor(model, link):
    for g in model.gazebo:
        if g.get('reference') == link and g.find('sensor') is not None:
            return g.find('sensor')
    raise AssertionError('no <sensor> for link %s' % link)


def test_links_and_diff_drive(model):
    assert {'base_link', 'wheel_left', 'wheel_right', 'caster', 'camera', 'lidar'} == set(model.links)
    files = [p.get('filename') for g in model.gazebo for p in g.iter('plugin')]
    assert 'libgazebo_ros_diff_drive.so' in files


def test_camera(model):
    s = sensor(model, 'camera')
    assert s.get('type') == 'camera'
    assert (s.findtext('camera/image/width'), s.findtext('camera/image/height')) == ('600', '400')
    p = s.find('plugin')
    assert p.get('filename') == 'libgazebo_ros_camera.so'
    assert (p.findtext('cameraName'), p.findtext('imageTopicName'), p.findtext('frameName')) == \
        ('diff_drive_robot/camera1', 'image_raw', 'camera')
    assert s.findtext('update_rate') == '30.0' and s.findtext('camera/horizontal_fov') == '1.3962634'


def test_lidar(model):
    s = sensor(model, 'lidar')
    assert s.get('type') == 'ray'
    h = s.find('ray/scan/horizontal')
    assert h.findtext('samples') == '720'
    assert float(h.findtext('min_angle')) == -0.785 and float(h.findtext('max_angle')) == 0.785
    assert (s.findtext('ray/range/min'), s.findtext('ray/range/max')) == ('0.03', '3.0')
    p = s.find('plugin')
    assert p.get('filename') == 'libgazebo_ros_laser.so'
    assert (p.findtext('topicName'), p.findtext('frameName')) == ('/diff_drive_robot/laser', 'lidar')
    assert (s.findtext('ray/noise/type'), s.findtext('ray/noise/stddev')) == ('gaussian', '0.01')


def test_lidar_sees_over_the_camera(model):
    cz = float(model.joints['camera_joint'].find('origin').get('xyz').split()[2])
    lz = float(model.joints['lidar_joint'].find('origin').get('xyz').split()[2])
    assert lz > cz + 0.025 + 0.005
