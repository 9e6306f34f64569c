"""controller_manager_msgs: every message and service has the md5 sum of ros_control Noetic 0.20.

The sums are those of the project's reference notes (INTERFACES.md 5.2); a field renamed,
retyped or reordered changes them.
"""

import pytest

from course_testing.msgs import generated_types, md5_of

NOETIC_MD5 = {
    ('msg', 'ControllerState'): 'aeb6b261d97793ab74099a3740245272',
    ('msg', 'HardwareInterfaceResources'): 'f25b55cbf1d1f76e82e5ec9e83f76258',
    ('srv', 'ListControllerTypes'): 'c1d4cd11aefa9f97ba4aeb5b33987f4e',
    ('srv', 'ListControllers'): '1341feb2e63fa791f855565d0da950d8',
    ('srv', 'LoadController'): '647e5c54b8d6468952d8d31f1efe96c0',
    ('srv', 'ReloadControllerLibraries'): '40e8c411fd1797d2e2c486018f846040',
    ('srv', 'SwitchController'): 'b29a7abc673b2c54c14b54e50f8d06a5',
    ('srv', 'UnloadController'): '647e5c54b8d6468952d8d31f1efe96c0',
}


@pytest.mark.parametrize('kind,name', sorted(NOETIC_MD5))
def test_generated_class_md5(kind, name):
    assert md5_of('controller_manager_msgs', kind, name) == NOETIC_MD5[(kind, name)]


def test_every_definition_is_checked():
    assert generated_types('controller_manager_msgs') == set(NOETIC_MD5)


def test_switch_controller_constants_and_fields():
    from controller_manager_msgs.srv import SwitchControllerRequest
    assert SwitchControllerRequest.BEST_EFFORT == 1
    assert SwitchControllerRequest.STRICT == 2
    assert SwitchControllerRequest.__slots__ == ['start_controllers', 'stop_controllers', 'strictness',
                                                 'start_asap', 'timeout']
