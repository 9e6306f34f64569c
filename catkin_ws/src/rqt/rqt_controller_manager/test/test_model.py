"""The Controller Manager plugin's logic without Qt or ROS."""
from collections import namedtuple

from rqt_controller_manager.model import (append_ns, menu_for, resolve_controllers_ns, resource_tree,
                                          table_rows)

C = namedtuple('C', 'name state type claimed_resources')
R = namedtuple('R', 'hardware_interface resources')


def test_controllers_namespace_is_one_level_up():
    assert '/robot' == resolve_controllers_ns('/robot/controller_manager')
    assert '/' == resolve_controllers_ns('/controller_manager')
    assert '/' == resolve_controllers_ns('/')
    assert '/a/b' == resolve_controllers_ns('/a/b/cm/')
    assert '/robot/controller_manager/load_controller' == append_ns('/robot/controller_manager', 'load_controller')
    assert '/jsc' == append_ns('/', 'jsc')


def test_rows_loaded_first_then_configured():
    loaded = [C('jsc', 'running', 'joint_state_controller/JointStateController', []),
              C('arm', 'stopped', 'position_controllers/JointTrajectoryController', [])]
    rows = table_rows(loaded, {'arm': 'x', 'gripper': 'effort_controllers/JointPositionController', 'b': 't'})
    assert [(r.name, r.state) for r in rows] == [('jsc', 'running'), ('arm', 'stopped'), ('b', 'uninitialized'),
                                                 ('gripper', 'uninitialized')]
    assert rows[3].type == 'effort_controllers/JointPositionController'


def test_menu_as_the_original():
    assert menu_for('running') == [('Stop', ['stop']), ('Stop and Unload', ['stop', 'unload'])]
    assert menu_for('stopped') == [('Start again', ['start']), ('Unload', ['unload'])]
    assert menu_for('initialized') == [('Start', ['start']), ('Unload', ['unload'])]
    assert menu_for('uninitialized') == [('Load', ['load']), ('Load and Start', ['load', 'start'])]
    assert menu_for('aborted') == []


def test_resource_tree():
    row = table_rows([C('m', 'running', 't', [R('hardware_interface::EffortJointInterface', ['j1', 'j2']),
                                              R('hardware_interface::VelocityJointInterface', ['j3'])])], {})[0]
    assert resource_tree(row) == ('Claimed Resources', [('hardware_interface::EffortJointInterface', ['j1', 'j2']),
                                                        ('hardware_interface::VelocityJointInterface', ['j3'])])
