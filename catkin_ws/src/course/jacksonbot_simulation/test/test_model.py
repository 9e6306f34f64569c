"""jacksonbot_sim.urdf.xacro: passes check_urdf and the simulator checks and carries the
tutorial's plugins with the right joints, topics and frames; the room world is valid SDF."""
import os
import xml.etree.ElementTree as ET

import pytest

from my_robot_model import model_check as mc

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(scope='module')
def model():
    return mc.checked_model(os.path.join(PKG, 'urdf', 'jacksonbot_sim.urdf.xacro'),
                            root='base_footprint')


def plugins(model):
    return {p.get('filename'): p for g in model.gazebo for p in g.iter('plugin')}


def sensor_of(model, link):
    for g in model.gazebo:
        if g.get('reference') == link and g.find('sensor') is not None:
            return g.find('sensor')
    raise AssertionError('no sensor on %s' % link)


def test_diff_drive(model):
    p = plugins(model)['libgazebo_ros_diff_drive.so']
    assert p.findtext('leftJoint') in model.joints and p.findtext('rightJoint') in model.joints
    yl = float(model.joints[p.findtext('leftJoint')].find('origin').get('xyz').split()[1])
    yr = float(model.joints[p.findtext('rightJoint')].find('origin').get('xyz').split()[1])
    assert float(p.findtext('wheelSeparation')) == pytest.approx(yl - yr)
    assert float(p.findtext('wheelDiameter')) == pytest.approx(0.064)
    assert p.findtext('robotBaseFrame') == 'base_footprint'
    assert (p.findtext('commandTopic'), p.findtext('odometryTopic')) == ('cmd_vel', 'odom')


def test_friction_wheels_20_casters_0(model):
    mu = {g.get('reference'): float(g.findtext('mu1')) for g in model.gazebo if g.findtext('mu1')}
    assert mu['left_wheel_link'] == mu['right_wheel_link'] == 20.0
    assert mu['front_caster_link'] == mu['back_caster_link'] == 0.0


def test_sensors(model):
    lidar = sensor_of(model, 'laser_link')
    assert lidar.get('type') == 'ray' and lidar.findtext('ray/scan/horizontal/samples') == '360'
    assert lidar.find('plugin').findtext('topicName') == '/scan'
    imu = sensor_of(model, 'imu_link')
    assert imu.get('type') == 'imu'
    ip = imu.find('plugin')
    assert ip.get('filename') == 'libgazebo_ros_imu_sensor.so'
    assert (ip.findtext('topicName'), ip.findtext('frameName')) == ('imu', 'imu_link')
    assert float(ip.findtext('gaussianNoise')) > 0
    assert imu.find('imu/angular_velocity/x/noise').get('type') == 'gaussian'
    cam = sensor_of(model, 'camera_link')
    assert cam.get('type') == 'depth'
    cp = cam.find('plugin')
    assert cp.get('filename') == 'libgazebo_ros_openni_kinect.so'
    assert (cp.findtext('cameraName'), cp.findtext('depthImageTopicName'), cp.findtext('pointCloudTopicName')) == \
        ('camera_sensor', 'depth/image_raw', 'points')
    js = plugins(model)['libgazebo_ros_joint_state_publisher.so']
    assert [j.strip() for j in js.findtext('jointName').split(',')] == ['left_wheel_joint', 'right_wheel_joint']


def test_room_world():
    w = ET.parse(os.path.join(PKG, 'worlds', 'jackson_room.world')).getroot().find('world')
    walls = [m for m in w.findall('model') if m.get('name').startswith(('wall', 'partition'))]
    assert len(walls) >= 5 and all(m.findtext('static') == 'true' for m in walls)
    objects = [i.findtext('uri') for i in w.findall('include')]
    assert 'model://ground_plane' in objects and len(objects) >= 6
