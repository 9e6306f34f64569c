"""Lab 4 grader self-tests: the reference passes (2 variants), seeded faults fail with the
right reason."""
import pytest

from grading.selftest import crit, failed, run_cases

MODEL = 'urdf/lab4_robot.urdf.xacro'
WORLD = 'worlds/lab4.world'
CTRL = 'scripts/lab4_controller.py'
ROW1 = "dict(body=[0.200, 0.140, 0.090], lidar=[0.03, 3.0], camera=[1024, 960])"
DRIVE_PLUGIN = '''  <gazebo>
    <plugin name="differential_drive_controller" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>wheel_left_joint</leftJoint>
      <rightJoint>wheel_right_joint</rightJoint>
      <wheelSeparation>0.175</wheelSeparation>
      <wheelDiameter>0.1</wheelDiameter>
      <commandTopic>plugin_cmd_vel</commandTopic>
    </plugin>
  </gazebo>
</robot>'''
PRIMITIVES_WORLD = '''<?xml version="1.0"?>
<sdf version="1.4">
  <world name="default">
    <include><uri>model://sun</uri></include>
    <include><uri>model://ground_plane</uri></include>
    <gravity>0 0 -9.8</gravity>
    <model name="box1"><static>true</static><pose>2.2 0 0.2 0 0 0</pose>
      <link name="l"><collision name="c"><geometry><box><size>0.4 0.4 0.4</size></box></geometry></collision>
        <visual name="v"><geometry><box><size>0.4 0.4 0.4</size></box></geometry></visual></link></model>
    <model name="ball1"><static>true</static><pose>1 -1.6 0.2 0 0 0</pose>
      <link name="l"><collision name="c"><geometry><sphere><radius>0.2</radius></sphere></geometry></collision>
        <visual name="v"><geometry><sphere><radius>0.2</radius></sphere></geometry></visual></link></model>
    <model name="post1"><static>true</static><pose>0.4 1.8 0.3 0 0 0</pose>
      <link name="l"><collision name="c">
          <geometry><cylinder><radius>0.1</radius><length>0.6</length></cylinder></geometry></collision>
        <visual name="v"><geometry><cylinder><radius>0.1</radius><length>0.6</length></cylinder></geometry></visual>
      </link></model>
  </world>
</sdf>
'''
# the wheels as the book's §12.4 has them: effort_controllers' velocity controller, one per
# wheel, on the EffortJointInterface; a small node turns the control program's twist into wheel
# speeds. The same with position controllers must fail criterion 5.
CONFIG = 'config/lab4_control.yaml'
LAUNCH = 'launch/lab4.launch'
PER_WHEEL_CONFIG = '''diffrobot:
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: 50
  left_wheel_controller:
    type: effort_controllers/{kind}Controller
    joint: wheel_left_joint
    pid: {{p: 0.1, i: 1.0, d: 0.0, i_clamp: 1.0}}
  right_wheel_controller:
    type: effort_controllers/{kind}Controller
    joint: wheel_right_joint
    pid: {{p: 0.1, i: 1.0, d: 0.0, i_clamp: 1.0}}
'''
WHEEL_SPEEDS = '''#!/usr/bin/python3
"""cmd_vel (Twist) -> each wheel controller's command (Float64, rad/s)."""
import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Float64

rospy.init_node('wheel_speeds')
radius, separation = rospy.get_param('~wheel_radius', 0.05), rospy.get_param('~wheel_separation', 0.175)
left = rospy.Publisher('left_wheel_controller/command', Float64, queue_size=1)
right = rospy.Publisher('right_wheel_controller/command', Float64, queue_size=1)


def on_twist(m):
    left.publish(Float64((m.linear.x - m.angular.z * separation / 2) / radius))
    right.publish(Float64((m.linear.x + m.angular.z * separation / 2) / radius))


rospy.Subscriber('cmd_vel', Twist, on_twist, queue_size=1)
rospy.spin()
'''
SPAWNED = 'args="mobile_base_controller joint_state_controller --timeout 120"/>'
PER_WHEEL_SPAWNED = ('args="left_wheel_controller right_wheel_controller joint_state_controller --timeout 120"/>\n'
                     '  <node name="wheel_speeds" pkg="my_robot_simulation_control" type="wheel_speeds.py"'
                     ' ns="/diffrobot"/>')


def per_wheel(kind):
    """make_repo kwargs: the reference with effort_controllers/<kind>Controller on each wheel."""
    return {'edits': [(MODEL, 'hardware_interface/VelocityJointInterface', 'hardware_interface/EffortJointInterface'),
                      (LAUNCH, SPAWNED, PER_WHEEL_SPAWNED),
                      (LAUNCH, 'to="/diffrobot/mobile_base_controller/cmd_vel"', 'to="/diffrobot/cmd_vel"')],
            'add': {CONFIG: PER_WHEEL_CONFIG.format(kind=kind), 'scripts/wheel_speeds.py': WHEEL_SPEEDS}}


# groups, each run in parallel by a module fixture, so that one fixture stays well inside
# pytest's per-test timeout on a loaded 2-core machine
CASES_A = {
    'ref_v1': ('123451', {}),
    'ref_v0': ('334400', {}),
    'plugin_drive': ('123451', {'edits': [(MODEL, '</robot>', DRIVE_PLUGIN)]}),
    'does_not_build': ('123451', {'edits': [('CMakeLists.txt', 'catkin_package(', 'catkin_package(BROKEN')]}),
}
CASES_B = {
    'wrong_lidar_range': ('123451', {'edits': [(MODEL, ROW1, ROW1.replace('lidar=[0.03, 3.0]', 'lidar=[0.03, 3.5]'))]}),
    'primitives_only': ('123451', {'add': {WORLD: PRIMITIVES_WORLD}}),
    'never_moves': ('123451', {'edits': [(CTRL, "get_param('~speed', 0.2)", "get_param('~speed', 0.0)")]}),
}

CASES_C = {
    'effort_velocity': ('123451', per_wheel('JointVelocity')),
    'effort_position': ('123451', per_wheel('JointPosition')),
}


@pytest.fixture(scope='module')
def runs_a(tmp_path_factory):
    return run_cases('lab4', CASES_A, str(tmp_path_factory.mktemp('lab4a')), workers=4)


@pytest.fixture(scope='module')
def runs_b(tmp_path_factory):
    return run_cases('lab4', CASES_B, str(tmp_path_factory.mktemp('lab4b')), workers=3)


@pytest.mark.parametrize('name', ['ref_v1', 'ref_v0'])
def test_reference_passes(runs_a, name):
    rc, out, crits = crit(runs_a, name)
    assert rc == 0, out
    assert sorted(crits) == [str(i) for i in range(10)] and not failed(crits), out


def test_reference_v0_variant_values(runs_a):
    _, out, crits = crit(runs_a, 'ref_v0')
    assert '200x180x120 mm' in crits['2'][1] and '0.3-3 m' in crits['3'][1] and '960x840' in crits['4'][1], out


def test_plugin_drive(runs_a):
    rc, out, crits = crit(runs_a, 'plugin_drive')
    assert rc == 1 and '6' in failed(crits), out
    assert 'drive plugin libgazebo_ros_diff_drive.so' in crits['6'][1]


def test_wrong_lidar_range(runs_b):
    rc, out, crits = crit(runs_b, 'wrong_lidar_range')
    assert rc == 1 and failed(crits) == ['3'], out
    assert 'lidar /scan 0.03-3.5 m, the variant wants 0.03-3 m' in crits['3'][1]


def test_primitives_only(runs_b):
    rc, out, crits = crit(runs_b, 'primitives_only')
    assert rc == 1 and '1' in failed(crits), out
    assert '0 different non-primitive objects' in crits['1'][1]
    assert 'primitives do not count: box1, ball1, post1' in crits['1'][1]


def test_never_moves(runs_b):
    rc, out, crits = crit(runs_b, 'never_moves')
    assert rc == 1 and failed(crits) == ['7', '8'], out
    assert 'of sim time' in crits['7'][1] and 'at least 1.5 m and 1.0 m needed' in crits['7'][1]


def test_does_not_build(runs_a):
    rc, out, crits = crit(runs_a, 'does_not_build')
    assert rc == 1 and failed(crits) == [str(i) for i in range(10)], out
    assert 'does not build' in crits['0'][1] and 'not checked' in crits['1'][1]


@pytest.fixture(scope='module')
def runs_c(tmp_path_factory):
    return run_cases('lab4', CASES_C, str(tmp_path_factory.mktemp('lab4c')), workers=2)


def test_effort_velocity_controllers_pass(runs_c):
    """§12.4: the velocity controller taken from effort_controllers (EffortJointInterface)."""
    rc, out, crits = crit(runs_c, 'effort_velocity')
    assert rc == 0 and not failed(crits), out
    assert 'left_wheel_controller effort_controllers/JointVelocityController' in crits['5'][1], out
    assert 'wheels wheel_left_joint, wheel_right_joint by velocity' in crits['5'][1], out


def test_effort_position_controllers_fail(runs_c):
    rc, out, crits = crit(runs_c, 'effort_position')
    assert rc == 1 and '5' in failed(crits), out
    assert crits['5'][1].startswith('wheels not controlled by velocity: wheel_left_joint by left_wheel_controller '
                                    '(effort_controllers/JointPositionController, position)'), out
