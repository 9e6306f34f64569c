"""controller_manager_msgs.utils without a master: discovery of controller managers from the
service list, filters over ControllerState lists, controller names from parameters."""
import pytest

from controller_manager_msgs import utils
from controller_manager_msgs.msg import ControllerState, HardwareInterfaceResources as HIR

SERVICES = {}


def offer(ns, skip=(), bad_type=()):
    for name, srv_type in utils.cm_services.items():
        if name in skip:
            continue
        SERVICES[ns.rstrip('/') + '/' + name] = 'std_srvs/Empty' if name in bad_type else srv_type


@pytest.fixture
def master(monkeypatch):
    SERVICES.clear()
    offer('/')
    offer('/controller_manager')
    offer('/foo/robot/controller_manager1')
    offer('/foo/robot/controller_manager2')
    offer('/incomplete', skip=('load_controller',))
    offer('/bad_type', bad_type=('switch_controller',))
    SERVICES['/other/list_things'] = 'std_srvs/Empty'
    queries = []

    def get_service_list(node=None, namespace=None, include_nodes=False):
        queries.append(namespace)
        ns = (namespace or '/').rstrip('/') + '/'
        return [s for s in SERVICES if s.startswith(ns)]

    def get_service_type(name):
        return SERVICES.get(name)
    monkeypatch.setattr(utils.rosservice, 'get_service_list', get_service_list)
    monkeypatch.setattr(utils.rosservice, 'get_service_type', get_service_type)
    return queries


VALID = ['/', '/controller_manager', '/foo/robot/controller_manager1', '/foo/robot/controller_manager2']


def test_is_controller_manager(master):
    for ns in VALID:
        assert utils.is_controller_manager(ns), ns
    for ns in ('non_existent', '/incomplete', '/bad_type'):
        assert not utils.is_controller_manager(ns), ns


def test_get_controller_managers(master):
    assert VALID == utils.get_controller_managers()
    assert VALID[2:] == utils.get_controller_managers('/foo')
    assert VALID[2:] == utils.get_controller_managers('/foo/robot')
    assert VALID == utils.get_controller_managers(initial_guess=VALID[2:])
    # An initial guess is trusted without the full check (as the original warns).
    wrong = utils.get_controller_managers(initial_guess=['/incomplete', '/bad_type'])
    assert {'/incomplete', '/bad_type'} == set(wrong) - set(VALID)


def test_controller_manager_lister(master):
    lister = utils.ControllerManagerLister('/foo')
    assert VALID[2:] == lister()
    del SERVICES['/foo/robot/controller_manager2/list_controllers']
    assert VALID[2:3] == lister()


def ctrl(name, type_, state, claims):
    return ControllerState(name=name, type=type_, state=state,
                           claimed_resources=[HIR(hardware_interface=h, resources=r) for h, r in claims])


CONTROLLERS = [
    ctrl('jsc', 'joint_state_controller/JointStateController', 'running',
         [('hardware_interface::JointStateInterface', [])]),
    ctrl('arm', 'position_controllers/JointTrajectoryController', 'running',
         [('hardware_interface::PositionJointInterface', ['j1', 'j2'])]),
    ctrl('gripper', 'effort_controllers/JointPositionController', 'stopped',
         [('hardware_interface::EffortJointInterface', ['g1'])]),
    ctrl('multi', 'my/Multi', 'initialized',
         [('hardware_interface::EffortJointInterface', ['j3']),
          ('hardware_interface::VelocityJointInterface', ['j1', 'j4'])]),
]


def names(lst):
    return [c.name for c in lst]


def test_filters():
    assert ['arm'] == names(utils.filter_by_name(CONTROLLERS, 'arm'))
    assert ['arm', 'gripper'] == names(utils.filter_by_name(CONTROLLERS, 'r', match_substring=True))
    assert ['jsc', 'arm'] == names(utils.filter_by_state(CONTROLLERS, 'running'))
    assert ['gripper'] == names(utils.filter_by_type(CONTROLLERS, 'effort_controllers/JointPositionController'))
    assert ['arm'] == names(utils.filter_by_type(CONTROLLERS, 'Trajectory', match_substring=True))
    assert ['gripper', 'multi'] == names(
        utils.filter_by_hardware_interface(CONTROLLERS, 'hardware_interface::EffortJointInterface'))
    assert ['multi'] == names(utils.filter_by_hardware_interface(CONTROLLERS, 'Velocity', match_substring=True))
    assert ['arm'] == names(utils.filter_by_resources(CONTROLLERS, ['j1', 'j2']))
    assert ['arm', 'multi'] == names(utils.filter_by_resources(CONTROLLERS, ['j1', 'j3'], match_any=True))
    assert ['multi'] == names(utils.filter_by_resources(
        CONTROLLERS, ['j1'], hardware_interface='hardware_interface::VelocityJointInterface'))
    assert [] == utils.filter_by_resources(CONTROLLERS, ['j1', 'j3'])  # no single interface has both


def test_rosparam_controller_names(monkeypatch):
    import rosparam
    params = ['/foo/type', '/xxx/type/xxx', '/ns/bar/type', '/ns/yyy/type/yyy', '/ns/bar/joints', '/run_id']
    monkeypatch.setattr(rosparam, 'list_params', lambda ns: [p for p in params if p.startswith(ns)])
    assert ['foo'] == utils.get_rosparam_controller_names()
    assert ['bar'] == utils.get_rosparam_controller_names('/ns')
    assert ['bar'] == utils.get_rosparam_controller_names('/ns/')
