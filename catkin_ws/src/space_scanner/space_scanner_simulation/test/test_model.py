"""space_scanner_simulation's chassi_bot.urdf.xacro: the description's robot passes check_urdf
and the simulator checks; the skid-steer plugin names the four wheel joints with the right
geometry; the RPLidar, camera and IMU sensors are configured like the real parts."""
import os
import xml.etree.ElementTree as ET

import pytest

from my_robot_model import model_check as mc

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(scope='module')
def model():
    return mc.checked_model(os.path.join(PKG, 'urdf', 'chassi_bot.urdf.xacro'),
                            root='base_footprint')


@pytest.fixture(scope='module')
def skid_model():
    """drive:=skid_steer, the comparison variant."""
    urdf = mc.expand_xacro(os.path.join(PKG, 'urdf', 'chassi_bot.urdf.xacro'), args=['drive:=skid_steer'])
    assert mc.problems(urdf, root_frames=('base_footprint',), resolve=mc.rospack_resolver()) == []
    return mc.parse(urdf)


def test_ros_control_by_default(model):
    ps = [p for g in model.gazebo for p in g.iter('plugin')]
    names = [p.get('filename') for p in ps]
    assert 'libgazebo_ros_control.so' in names and 'libgazebo_ros_skid_steer_drive.so' not in names
    ctl = ps[names.index('libgazebo_ros_control.so')]
    assert ctl.findtext('robotNamespace') == '/'


def test_drive_arg_rejects_unknown():
    with pytest.raises(Exception):
        mc.expand_xacro(os.path.join(PKG, 'urdf', 'chassi_bot.urdf.xacro'), args=['drive:=tank'])


def test_skid_steer(skid_model):
    model = skid_model
    assert 'libgazebo_ros_control.so' not in [p.get('filename') for g in model.gazebo for p in g.iter('plugin')]
    ps = [p for g in model.gazebo for p in g.iter('plugin')
          if p.get('filename') == 'libgazebo_ros_skid_steer_drive.so']
    assert len(ps) == 1
    p = ps[0]
    joints = {t: p.findtext(t) for t in ('leftFrontJoint', 'rightFrontJoint', 'leftRearJoint', 'rightRearJoint')}
    xyz = {t: [float(v) for v in model.joints[j].find('origin').get('xyz').split()] for t, j in joints.items()}
    assert xyz['leftFrontJoint'][0] > 0 > xyz['leftRearJoint'][0]
    assert xyz['leftFrontJoint'][1] > 0 > xyz['rightFrontJoint'][1]
    assert float(p.findtext('wheelSeparation')) == pytest.approx(xyz['leftRearJoint'][1] - xyz['rightRearJoint'][1])
    r = float(model.links['left_front_wheel'].find('collision/geometry/cylinder').get('radius'))
    assert float(p.findtext('wheelDiameter')) == pytest.approx(2 * r)
    for tag in ('updateRate', 'torque', 'commandTopic', 'odometryTopic', 'odometryFrame', 'robotBaseFrame',
                'broadcastTF', 'covariance_x', 'covariance_y', 'covariance_yaw'):
        assert p.findtext(tag), tag
    assert p.findtext('robotBaseFrame') in model.links


def test_rplidar(model):
    s = [g.find('sensor') for g in model.gazebo if g.get('reference') == 'laser' and g.find('sensor') is not None][0]
    assert s.findtext('ray/scan/horizontal/samples') == '360'
    assert float(s.findtext('ray/range/min')) == 0.15 and float(s.findtext('ray/range/max')) == 12.0
    assert 5.5 <= float(s.findtext('update_rate')) <= 10
    assert s.find('plugin').findtext('frameName') == 'laser'


def test_description_package_untouched_by_simulation_tags():
    """The plugins live here; the description keeps only its friction tags."""
    desc = mc.expand_xacro(os.path.join(mc.rospack_resolver()('package://space_scanner_description/urdf'),
                                        'chassi_bot.urdf.xacro'))
    assert '<plugin' not in desc and '<sensor' not in desc


def test_office_world():
    w = ET.parse(os.path.join(PKG, 'worlds', 'office.world')).getroot().find('world')
    uris = [i.findtext('uri') for i in w.findall('include')]
    assert 'model://office' in uris and 'model://ground_plane' in uris
