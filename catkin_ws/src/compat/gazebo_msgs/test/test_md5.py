"""gazebo_msgs: every message and service has the md5 sum of ROS Noetic's gazebo_msgs 2.9.2.

The sums were taken from the project's reference notes (INTERFACES.md 6.3) and from code
generated from the original definitions; a field renamed, retyped or reordered changes them.
"""
import subprocess

import pytest

from course_testing.msgs import generated_types, md5_of

NOETIC_MD5 = {
    ('msg', 'ContactState'): '48c0ffb054b8c444f870cecea1ee50d9',
    ('msg', 'ContactsState'): 'acbcb1601a8e525bf72509f18e6f668d',
    ('msg', 'LinkState'): '0818ebbf28ce3a08d48ab1eaa7309ebe',
    ('msg', 'LinkStates'): '48c080191eb15c41858319b4d8a609c2',
    ('msg', 'ModelState'): '9330fd35f2fcd82d457e54bd54e10593',
    ('msg', 'ModelStates'): '48c080191eb15c41858319b4d8a609c2',
    ('msg', 'ODEJointProperties'): '1b744c32a920af979f53afe2f9c3511f',
    ('msg', 'ODEPhysics'): '667d56ddbd547918c32d1934503dc335',
    ('msg', 'PerformanceMetrics'): '884f71fd5037b886ec5e126b83c4425a',
    ('msg', 'SensorPerformanceMetric'): '01762ded18cfe9ebc7c8222667c99547',
    ('msg', 'WorldState'): 'de1a9de3ab7ba97ac0e9ec01a4eb481e',
    ('srv', 'ApplyBodyWrench'): '585b9f9618aa0581b207e2f2d90866bc',
    ('srv', 'ApplyJointEffort'): 'c0039811b8cc919490b3cff748cdf46b',
    ('srv', 'BodyRequest'): '5eade9afe7f232d78005bd0cafeab755',
    ('srv', 'DeleteLight'): 'ae11ea8100d536d5b92c2b5917abf912',
    ('srv', 'DeleteModel'): '9ce56b4e9e54616de25d796dc972a262',
    ('srv', 'GetJointProperties'): '7b30be900f50aa21efec4a0ec92d91c9',
    ('srv', 'GetLightProperties'): 'df2cef87e13e2e6990e81e8aaa454c19',
    ('srv', 'GetLinkProperties'): '0e06a70386d0ee3fb880c02f23fcd821',
    ('srv', 'GetLinkState'): '09d6c98cce97b35f7ab9bd70300657ab',
    ('srv', 'GetModelProperties'): '5717f7bd34ed990fa80e28b3015027a3',
    ('srv', 'GetModelState'): '4c515e936d3319c9610c559c60bfc3d4',
    ('srv', 'GetPhysicsProperties'): '575a5e74786981b7df2e3afc567693a6',
    ('srv', 'GetWorldProperties'): '36bb0f2eccf4d8be971410c22818ba3f',
    ('srv', 'JointRequest'): '0be1351618e1dc030eb7959d9a4902de',
    ('srv', 'SetJointProperties'): '15a76e921b1410c698d82782ea5fa370',
    ('srv', 'SetJointTrajectory'): '88f5c10979e3f9649d5ae87a3b12aa65',
    ('srv', 'SetLightProperties'): 'e6f13430c57278bb364aca53a1bf5ebf',
    ('srv', 'SetLinkProperties'): 'd534ce1b36ee99de0ffa806c3a6348f0',
    ('srv', 'SetLinkState'): '8a5146eb66ae4d26b0860b08f3f271be',
    ('srv', 'SetModelConfiguration'): '10e3139d3b669c40afc057d38956fff7',
    ('srv', 'SetModelState'): '5b3ab0281d4f5445def017e3a2e4a07b',
    ('srv', 'SetPhysicsProperties'): '97e2057080558ce4730434b5fae75c91',
    ('srv', 'SpawnModel'): '9ed9c82c96abe1a00c3e8cdaeee24413',
}


@pytest.mark.parametrize('kind,name', sorted(NOETIC_MD5))
def test_generated_class_md5(kind, name):
    assert md5_of('gazebo_msgs', kind, name) == NOETIC_MD5[(kind, name)]


def test_every_definition_is_checked():
    assert generated_types('gazebo_msgs') == set(NOETIC_MD5)


@pytest.mark.parametrize('tool,name', [('rosmsg', 'gazebo_msgs/ModelStates'),
                                       ('rossrv', 'gazebo_msgs/SpawnModel')])
def test_command_line_md5(tool, name):
    """rosmsg/rossrv compute the sum from the .msg/.srv files found on ROS_PACKAGE_PATH."""
    out = subprocess.run([tool, 'md5', name], capture_output=True, text=True, timeout=60)
    kind = 'msg' if tool == 'rosmsg' else 'srv'
    assert out.stdout.strip() == NOETIC_MD5[(kind, name.split('/')[1])], out.stderr


def test_spawn_model_fields_in_order():
    from gazebo_msgs.srv import SpawnModelRequest, SpawnModelResponse
    assert SpawnModelRequest.__slots__ == ['model_name', 'model_xml', 'robot_namespace',
                                           'initial_pose', 'reference_frame']
    assert SpawnModelResponse.__slots__ == ['success', 'status_message']
