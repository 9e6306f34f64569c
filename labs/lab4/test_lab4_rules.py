"""Lab 4 rules without ROS: scene analysis, motion metrics, collision detection, evaluate()."""
import math
import os

import pytest

from grading.lab4.motion import motion, pushed
from grading.lab4.rules import evaluate
from grading.lab4.scene import SceneError, analyse_scene, scene_verdict

HERE = os.path.dirname(os.path.abspath(__file__))
REF = os.path.join(HERE, 'reference', 'my_robot_simulation_control')
MODELS = os.path.join(os.path.dirname(HERE), '..', 'catkin_ws', 'src', 'sim', 'ode_sim', 'models')


def q(yaw):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def track(points):
    """[(t, x, y, yaw)] -> model_states track tuples."""
    return [(t, x, y, 0.0) + q(yaw) for t, x, y, yaw in points]


def test_reference_scene():
    with open(os.path.join(REF, 'worlds', 'lab4.world')) as f:
        scene = analyse_scene(f.read())
    ok, _ru, en = scene_verdict(scene, [MODELS])
    assert ok, en
    assert 'barrel, chair, potted_plant, traffic_cone, trash_bin' in en


def test_scene_problems():
    text = '''<sdf version="1.6"><world name="w">
      <model name="b"><link name="l">
        <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision></link></model>
      <include><uri>model://barrel</uri></include>
      <include><uri>model://barrel</uri><name>barrel2</name></include>
      <model name="m"><link name="l">
        <visual name="v"><geometry><mesh><uri>file://x.stl</uri></mesh></geometry></visual></link></model>
    </world></sdf>'''
    ok, _ru, en = scene_verdict(analyse_scene(text), [MODELS])
    assert not ok
    assert en.startswith('no light (<light> or model://sun); no ground')
    assert 'no <gravity> with z < 0' in en
    assert '2 different non-primitive objects (barrel, m), at least 3 needed (primitives do not count: b)' in en


def test_scene_not_xml():
    with pytest.raises(SceneError):
        analyse_scene('<sdf><world>')


def test_motion_straight():
    m = motion(track([(t * 0.1, 0.02 * t, 0.0, 0.0) for t in range(401)]))
    assert m['path'] == pytest.approx(8.0) and m['reach'] == pytest.approx(8.0)
    assert m['turned'] == pytest.approx(0.0) and m['reversals'] == 0


def test_motion_spin_in_place():
    m = motion(track([(t * 0.1, 0.0, 0.0, 0.1 * t) for t in range(401)]))
    assert m['path'] == pytest.approx(0.0) and m['turned'] == pytest.approx(40.0)


def test_motion_oscillation():
    pts = [(t * 0.1, 0.5 * math.sin(t * 0.1 * 2 * math.pi / 4), 0.0, 0.0) for t in range(401)]
    m = motion(track(pts))
    assert m['reversals'] >= 15


def test_pushed():
    a = (1.0, 0.0, 0.0) + q(0.0)
    objs = {'still': (a, a), 'pushed': (a, (1.1, 0.0, 0.0) + q(0.0)), 'turned': (a, (1.0, 0.0, 0.0) + q(0.5))}
    assert [n for n, _, _ in pushed(objs)] == ['pushed', 'turned']


def obs(track_pts, objects=None, **launch):
    with open(os.path.join(REF, 'worlds', 'lab4.world')) as f:
        world = f.read()
    base = {'robot_description': None, 'scans': {'/scan': (0.03, 3.0)}, 'images': {'/camera/image_raw': (1024, 960)},
            'controllers': {}, 'motion': {'robot': 'bot', 'track': track(track_pts), 'objects': objects or {}}}
    base.update(launch)
    return {'isu': '123451', 'model_dirs': [MODELS], 'scene': {'path': 'lab4.world', 'text': world}, 'launch': base}


def test_evaluate_spin_fails_8():
    pts = [(t * 0.1, 0.005 * t, 0.0, 0.3 * t) for t in range(401)]   # 2 m, 120 rad
    crits = {c.id: c for c in evaluate(obs(pts))}
    assert crits['7'].passed and not crits['8'].passed
    assert crits['8'].reason['en'].startswith('spinning in place: turned 120.0 rad over 2.00 m')
    assert not crits['2'].passed and 'did not appear' in crits['2'].reason['en']
    assert crits['3'].passed and crits['4'].passed and crits['1'].passed


def test_evaluate_collision_fails_9():
    a = (2.2, 0.0, 0.0) + q(0.0)
    pts = [(t * 0.1, 0.05 * t, 0.0, 0.0) for t in range(401)]
    crits = {c.id: c for c in evaluate(obs(pts, {'barrel': (a, (2.5, 0.1, 0.0) + q(0.0))}))}
    assert not crits['9'].passed and crits['9'].reason['en'] == 'collision: barrel (moved 0.32 m)'


def test_evaluate_short_run_says_wall_clock():
    pts = [(t * 0.1, 0.0, 0.0, 0.0) for t in range(101)]
    crits = {c.id: c for c in evaluate(obs(pts))}
    assert not crits['7'].passed
    assert 'only 10.0 s of sim time passed within 240 s of wall clock' in crits['7'].reason['en']


def ctrl(ctype, iface, joints=('wheel_left_joint', 'wheel_right_joint'), state='running'):
    return {'state': state, 'type': ctype, 'claimed': [('hardware_interface::' + iface, list(joints))]}


WHEEL = ('<link name="wheel_{s}">'
         '<collision><geometry><cylinder radius="0.05" length="0.025"/></geometry></collision></link>'
         '<joint name="wheel_{s}_joint" type="continuous"><parent link="base_link"/><child link="wheel_{s}"/></joint>')
ROBOT = ('<robot name="bot">'
         '<link name="base_link"><collision><geometry><box size="0.2 0.14 0.09"/></geometry></collision></link>'
         + WHEEL.format(s='left') + WHEEL.format(s='right') + '</robot>')


def crit5(controllers):
    desc = ROBOT
    o = obs([(t * 0.1, 0.05 * t, 0.0, 0.0) for t in range(401)], robot_description=desc,
            controllers=dict(controllers, joint_state_controller=ctrl('joint_state_controller/JointStateController',
                                                                      'JointStateInterface', ())))
    return {c.id: c for c in evaluate(o)}['5']


@pytest.mark.parametrize('ctype,iface', [
    ('effort_controllers/JointVelocityController', 'EffortJointInterface'),     # the book's §12.4
    ('velocity_controllers/JointVelocityController', 'VelocityJointInterface'),
    ('velocity_controllers/JointGroupVelocityController', 'VelocityJointInterface'),
    ('diff_drive_controller/DiffDriveController', 'VelocityJointInterface'),
    ('my_pkg/MyWheelController', 'VelocityJointInterface'),                     # unknown type: by interface
])
def test_wheels_by_velocity_pass(ctype, iface):
    if 'Group' in ctype or 'DiffDrive' in ctype or 'My' in ctype:
        c = crit5({'wheels': ctrl(ctype, iface)})
    else:
        c = crit5({'left': ctrl(ctype, iface, ['wheel_left_joint']),
                   'right': ctrl(ctype, iface, ['wheel_right_joint'])})
    assert c.passed, c.reason['en']
    assert 'wheels wheel_left_joint, wheel_right_joint by velocity' in c.reason['en']


@pytest.mark.parametrize('ctype,iface,what', [
    ('effort_controllers/JointPositionController', 'EffortJointInterface', 'position'),    # PW5's position control
    ('velocity_controllers/JointPositionController', 'VelocityJointInterface', 'position'),
    ('position_controllers/JointGroupPositionController', 'PositionJointInterface', 'position'),
    ('velocity_controllers/JointTrajectoryController', 'VelocityJointInterface', 'trajectory'),
    ('effort_controllers/JointEffortController', 'EffortJointInterface', 'effort'),
    ('my_pkg/MyWheelController', 'EffortJointInterface', 'a type the grader does not know, under EffortJointInterface'),
])
def test_wheels_by_position_or_effort_fail(ctype, iface, what):
    c = crit5({'wheels': ctrl(ctype, iface)})
    assert not c.passed
    assert c.reason['en'].startswith('wheels not controlled by velocity: wheel_left_joint by wheels (%s, %s), '
                                     'wheel_right_joint by wheels (%s, %s); a velocity controller is needed'
                                     % (ctype, what, ctype, what)), c.reason['en']


def test_one_wheel_without_controller():
    c = crit5({'left': ctrl('effort_controllers/JointVelocityController', 'EffortJointInterface',
                            ['wheel_left_joint'])})
    assert not c.passed and 'wheel_right_joint by no running controller' in c.reason['en']
    stopped = crit5({'wheels': ctrl('diff_drive_controller/DiffDriveController', 'VelocityJointInterface',
                                    state='stopped')})
    assert not stopped.passed and 'controllers not running: wheels (stopped)' in stopped.reason['en']
