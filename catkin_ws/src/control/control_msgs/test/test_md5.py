"""control_msgs: every message, action message and service has the md5 sum of ROS 1's
control_msgs 1.5.2 (Noetic).

The sums are those of code generated from the original definitions (rosserial, roslisp and
other generators' output for control_msgs); JointControllerState, PidState, JointTolerance,
GripperCommand, JointJog, JointTrajectoryControllerState, the Goal/Result/Feedback of every
action and QueryTrajectoryState were checked one by one. A field renamed, retyped or reordered
changes them.
"""
import subprocess

import pytest

from course_testing.msgs import generated_types, md5_of

NOETIC_MD5 = {
    ('msg', 'FollowJointTrajectoryAction'): 'bc4f9b743838566551c0390c65f1a248',
    ('msg', 'FollowJointTrajectoryActionFeedback'): 'd8920dc4eae9fc107e00999cce4be641',
    ('msg', 'FollowJointTrajectoryActionGoal'): 'cff5c1d533bf2f82dd0138d57f4304bb',
    ('msg', 'FollowJointTrajectoryActionResult'): 'c4fb3b000dc9da4fd99699380efcc5d9',
    ('msg', 'FollowJointTrajectoryFeedback'): '10817c60c2486ef6b33e97dcd87f4474',
    ('msg', 'FollowJointTrajectoryGoal'): '69636787b6ecbde4d61d711979bc7ecb',
    ('msg', 'FollowJointTrajectoryResult'): '493383b18409bfb604b4e26c676401d2',
    ('msg', 'GripperCommand'): '680acaff79486f017132a7f198d40f08',
    ('msg', 'GripperCommandAction'): '950b2a6ebe831f5d4f4ceaba3d8be01e',
    ('msg', 'GripperCommandActionFeedback'): '653dff30c045f5e6ff3feb3409f4558d',
    ('msg', 'GripperCommandActionGoal'): 'aa581f648a35ed681db2ec0bf7a82bea',
    ('msg', 'GripperCommandActionResult'): '143702cb2df0f163c5283cedc5efc6b6',
    ('msg', 'GripperCommandFeedback'): 'e4cbff56d3562bcf113da5a5adeef91f',
    ('msg', 'GripperCommandGoal'): '86fd82f4ddc48a4cb6856cfa69217e43',
    ('msg', 'GripperCommandResult'): 'e4cbff56d3562bcf113da5a5adeef91f',
    ('msg', 'JointControllerState'): '987ad85e4756f3aef7f1e5e7fe0595d1',
    ('msg', 'JointJog'): '1685da700c8c2e1254afc92a5fb89c96',
    ('msg', 'JointTolerance'): 'f544fe9c16cf04547e135dd6063ff5be',
    ('msg', 'JointTrajectoryAction'): 'a04ba3ee8f6a2d0985a6aeaf23d9d7ad',
    ('msg', 'JointTrajectoryActionFeedback'): 'aae20e09065c3809e8a8e87c4c8953fd',
    ('msg', 'JointTrajectoryActionGoal'): 'a99e83ef6185f9fdd7693efe99623a86',
    ('msg', 'JointTrajectoryActionResult'): '1eb06eeff08fa7ea874431638cb52332',
    ('msg', 'JointTrajectoryControllerState'): '10817c60c2486ef6b33e97dcd87f4474',
    ('msg', 'JointTrajectoryFeedback'): 'd41d8cd98f00b204e9800998ecf8427e',
    ('msg', 'JointTrajectoryGoal'): '2a0eff76c870e8595636c2a562ca298e',
    ('msg', 'JointTrajectoryResult'): 'd41d8cd98f00b204e9800998ecf8427e',
    ('msg', 'PidState'): 'b138ec00e886c10e73f27e8712252ea6',
    ('msg', 'PointHeadAction'): '7252920f1243de1b741f14f214125371',
    ('msg', 'PointHeadActionFeedback'): '33c9244957176bbba97dd641119e8460',
    ('msg', 'PointHeadActionGoal'): 'b53a8323d0ba7b310ba17a2d3a82a6b8',
    ('msg', 'PointHeadActionResult'): '1eb06eeff08fa7ea874431638cb52332',
    ('msg', 'PointHeadFeedback'): 'cce80d27fd763682da8805a73316cab4',
    ('msg', 'PointHeadGoal'): '8b92b1cd5e06c8a94c917dc3209a4c1d',
    ('msg', 'PointHeadResult'): 'd41d8cd98f00b204e9800998ecf8427e',
    ('msg', 'SingleJointPositionAction'): 'c4a786b7d53e5d0983decf967a5a779e',
    ('msg', 'SingleJointPositionActionFeedback'): '3503b7cf8972f90d245850a5d8796cfa',
    ('msg', 'SingleJointPositionActionGoal'): '4b0d3d091471663e17749c1d0db90f61',
    ('msg', 'SingleJointPositionActionResult'): '1eb06eeff08fa7ea874431638cb52332',
    ('msg', 'SingleJointPositionFeedback'): '8cee65610a3d08e0a1bded82f146f1fd',
    ('msg', 'SingleJointPositionGoal'): 'fbaaa562a23a013fd5053e5f72cbb35c',
    ('msg', 'SingleJointPositionResult'): 'd41d8cd98f00b204e9800998ecf8427e',
    ('srv', 'QueryCalibrationState'): '28af3beedcb84986b8e470dc5470507d',
    ('srv', 'QueryTrajectoryState'): 'ec93cdecbd8062d761aa52b7c90cd44b',
}


@pytest.mark.parametrize('kind,name', sorted(NOETIC_MD5))
def test_generated_class_md5(kind, name):
    assert md5_of('control_msgs', kind, name) == NOETIC_MD5[(kind, name)]


def test_every_definition_is_checked():
    assert generated_types('control_msgs') == set(NOETIC_MD5)


@pytest.mark.parametrize('tool,name', [('rosmsg', 'control_msgs/JointControllerState'),
                                       ('rosmsg', 'control_msgs/PidState'),
                                       ('rossrv', 'control_msgs/QueryTrajectoryState')])
def test_command_line_md5(tool, name):
    """rosmsg/rossrv compute the sum from the files found on ROS_PACKAGE_PATH."""
    out = subprocess.run([tool, 'md5', name], capture_output=True, text=True, timeout=60)
    kind = 'msg' if tool == 'rosmsg' else 'srv'
    assert out.stdout.strip() == NOETIC_MD5[(kind, name.split('/')[1])], out.stderr


def test_joint_controller_state_fields_in_order():
    from control_msgs.msg import JointControllerState
    assert JointControllerState.__slots__ == [
        'header', 'set_point', 'process_value', 'process_value_dot', 'error', 'time_step',
        'command', 'p', 'i', 'd', 'i_clamp', 'antiwindup']
