"""spawner / controller_manager CLI logic without a ROS master (fake services)."""
import pytest

from controller_manager import cli
from controller_manager import spawner as logic


class FakeLog(object):
    def __init__(self):
        self.lines = []

    def info(self, msg):
        self.lines.append(('info', msg))

    def warn(self, msg):
        self.lines.append(('warn', msg))

    def error(self, msg):
        self.lines.append(('error', msg))


class FakeServices(object):
    def __init__(self, fail_load=(), fail_switch=False):
        self.calls = []
        self.fail_load = set(fail_load)
        self.fail_switch = fail_switch

    def load(self, name):
        self.calls.append(('load', name))
        return name not in self.fail_load

    def switch(self, start, stop, strictness):
        self.calls.append(('switch', start, stop, strictness))
        return not self.fail_switch

    def unload(self, name):
        self.calls.append(('unload', name))
        return True


def test_parse_args_defaults_and_timeouts():
    a = logic.parse_args(['a', 'b'])
    assert a.controllers == ['a', 'b'] and not a.stopped and a.timeout == 30 and a.namespace is None
    assert logic.parse_args(['a', '--no-timeout']).timeout == 0.0
    assert logic.parse_args(['a', '--timeout', '-1']).timeout == 0.0
    assert logic.parse_args(['a', '--timeout', '5']).timeout == 5.0
    a = logic.parse_args(['--stopped', '--wait-for', '/ready', '--namespace', '/robot',
                          '--shutdown-timeout', '3', 'x'])
    assert a.stopped and a.wait_for == '/ready' and a.namespace == '/robot' and a.shutdown_timeout == 3
    with pytest.raises(SystemExit):
        logic.parse_args([])


def test_service_prefix():
    assert logic.service_prefix(None) == 'controller_manager/'
    assert logic.service_prefix('/robot/') == '/robot/controller_manager/'
    assert logic.service_prefix('robot') == 'robot/controller_manager/'


def test_expand_controllers_yaml_files(tmp_path):
    f = tmp_path / 'c.yaml'
    f.write_text('jsc:\n  type: joint_state_controller/JointStateController\n  publish_rate: 50\n'
                 'wheel:\n  type: velocity_controllers/JointVelocityController\n  joint: j\n')
    params = {}
    names = logic.expand_controllers(['first', str(f), 'last'], params.__setitem__)
    assert names == ['first', 'jsc', 'wheel', 'last']
    assert params['jsc']['publish_rate'] == 50
    assert params['wheel']['joint'] == 'j'


def test_expand_controllers_bad_yaml(tmp_path):
    f = tmp_path / 'bad.yaml'
    f.write_text('- just\n- a list\n')
    with pytest.raises(logic.SpawnerError, match='expected a mapping'):
        logic.expand_controllers([str(f)], lambda k, v: None)
    f.write_text('a: [unclosed\n')
    with pytest.raises(logic.SpawnerError, match='cannot read'):
        logic.expand_controllers([str(f)], lambda k, v: None)


def test_spawner_loads_starts_and_tears_down_in_reverse():
    services, log = FakeServices(), FakeLog()
    s = logic.Spawner(services, log)
    s.load_all(['a', 'b', 'c'])
    assert s.start_all()
    s.teardown()
    s.teardown()  # only once
    assert services.calls == [('load', 'a'), ('load', 'b'), ('load', 'c'),
                              ('switch', ['a', 'b', 'c'], [], logic.STRICT),
                              ('switch', [], ['a', 'b', 'c'], logic.STRICT),
                              ('unload', 'c'), ('unload', 'b'), ('unload', 'a')]
    msgs = [m for _, m in log.lines]
    assert 'Loading controller: a' in msgs
    assert 'Controller Spawner: Loaded controllers: a, b, c' in msgs
    assert 'Started controllers: a, b, c' in msgs


def test_spawner_failed_load_is_skipped():
    services, log = FakeServices(fail_load={'b'}), FakeLog()
    s = logic.Spawner(services, log)
    assert s.load_all(['a', 'b']) == ['a']
    assert ('error', 'Failed to load b') in log.lines
    s.start_all()
    assert ('switch', ['a'], [], logic.STRICT) in services.calls


def test_spawner_stopped_only_loads():
    services, log = FakeServices(), FakeLog()
    s = logic.Spawner(services, log, autostart=False)
    s.load_all(['a'])
    assert s.start_all()
    assert [c for c in services.calls if c[0] == 'switch'] == []
    s.teardown()
    assert services.calls[-2:] == [('switch', [], ['a'], logic.BEST_EFFORT), ('unload', 'a')]


def test_spawner_failed_start_logged():
    services, log = FakeServices(fail_switch=True), FakeLog()
    s = logic.Spawner(services, log)
    s.load_all(['a'])
    assert not s.start_all()
    assert ('error', 'Failed to start controllers: a') in log.lines


def test_spawner_teardown_survives_service_errors():
    class Broken(FakeServices):
        def switch(self, start, stop, strictness):
            raise RuntimeError('service went away')
    log = FakeLog()
    s = logic.Spawner(Broken(), log)
    s.loaded = ['a']
    s.teardown()
    assert any(level == 'warn' and 'error while taking down controllers' in m for level, m in log.lines)


class FakeApi(object):
    def __init__(self):
        self.calls = []

    def __getattr__(self, name):
        def f(*args, **kwargs):
            self.calls.append((name, args, kwargs))
            return True
        return f


@pytest.mark.parametrize('argv,calls', [
    (['lt'], [('list_controller_types', (), {})]),
    (['list-types'], [('list_controller_types', (), {})]),
    (['lc'], [('list_controllers', (), {})]),
    (['load', 'a', 'b'], [('load_controller', ('a',), {}), ('load_controller', ('b',), {})]),
    (['unload', 'a'], [('unload_controller', ('a',), {})]),
    (['start', 'a'], [('start_controller', ('a',), {})]),
    (['stop', 'a'], [('stop_controller', ('a',), {})]),
    (['load'], []),
    (['sp', 'a', 'b'], [('load_controller', ('a',), {}), ('load_controller', ('b',), {}),
                        ('start_controller', ('a',), {}), ('start_controller', ('b',), {})]),
    (['kl', 'a', 'b'], [('stop_controller', ('a',), {}), ('stop_controller', ('b',), {}),
                        ('unload_controller', ('a',), {}), ('unload_controller', ('b',), {})]),
    (['reload-libraries'], [('reload_libraries', (True,), {'restore': False})]),
    (['reload-libraries', '--restore'], [('reload_libraries', (True,), {'restore': True})]),
])
def test_cli_commands(argv, calls):
    api = FakeApi()
    assert cli.main(argv, api) == 0
    assert api.calls == calls


def test_cli_usage(capsys):
    assert cli.main([], FakeApi()) == 0  # as the original: usage, exit 0
    assert 'reload-libraries     - Reloads all plugin controller libraries' in capsys.readouterr().out
    assert cli.main(['nope'], FakeApi()) == 1
    out, err = capsys.readouterr()
    assert err == "controller_manager: unknown command 'nope'\n"
    assert out.startswith('Commands:\n    load <name>')


def test_cli_failure_exit_code():
    class Failing(FakeApi):
        def load_controller(self, name):
            return False
    assert cli.main(['load', 'a'], Failing()) == 1


class FakeSrv(object):
    """Stands in for a rospy.ServiceProxy: records requests, answers ok."""
    def __init__(self, calls, name, ok=True, response=None):
        self.calls, self.name, self.ok, self.response = calls, name, ok, response

    def call(self, *args, **kwargs):
        self.calls.append((self.name, args, kwargs))
        if self.response is not None:
            return self.response
        return type('Resp', (), {'ok': self.ok})()

    __call__ = call


def fake_services(monkeypatch, ok=True, controllers=()):
    from controller_manager import controller_manager_interface as cmi
    from controller_manager_msgs.srv import ListControllersResponse
    calls = []

    def proxy(service, srv_type, namespace=None, wait=True):
        resp = ListControllersResponse(controller=list(controllers)) if service == 'list_controllers' else None
        return FakeSrv(calls, service, ok, resp)
    monkeypatch.setattr(cmi, '_proxy', proxy)
    return cmi, calls


def test_interface_output_as_the_original(monkeypatch, capsys):
    from controller_manager_msgs.msg import ControllerState, HardwareInterfaceResources
    c1 = ControllerState(name='my_controller1', state='running', claimed_resources=[
        HardwareInterfaceResources(hardware_interface='hardware_interface::EffortJointInterface', resources=['j1'])])
    c2 = ControllerState(name='jsc', state='initialized', claimed_resources=[
        HardwareInterfaceResources(hardware_interface='hardware_interface::VelocityJointInterface'),
        HardwareInterfaceResources(hardware_interface='hardware_interface::EffortJointInterface')])
    cmi, calls = fake_services(monkeypatch, controllers=[c1, c2])
    cmi.list_controllers()
    assert cmi.load_controller('my_controller1')
    assert cmi.unload_controller('my_controller1')
    assert cmi.start_controller('a')
    assert cmi.stop_controllers(['a', 'b'])
    assert cmi.start_controllers(('a', 'b'))
    assert cmi.reload_libraries(True)
    assert capsys.readouterr().out == (
        "'my_controller1' - 'hardware_interface::EffortJointInterface' ( running )\n"
        "'jsc' - 'hardware_interface::EffortJointInterface+hardware_interface::VelocityJointInterface'"
        " ( initialized )\n"
        "Loaded 'my_controller1'\n"
        "Unloaded 'my_controller1' successfully\n"
        "Started ['a'] successfully\n"
        "Stopped ['a', 'b'] successfully\n"
        "Started ('a', 'b') successfully\n"
        "Restore: False\nSuccessfully reloaded libraries\n")
    switch = [c for c in calls if c[0] == 'switch_controller'][0][1][0]
    assert (['a'], [], 2) == (switch.start_controllers, switch.stop_controllers, switch.strictness)


def test_interface_failures_as_the_original(monkeypatch, capsys):
    cmi, calls = fake_services(monkeypatch, ok=False)
    assert not cmi.load_controller('x')
    assert not cmi.unload_controller('x')
    assert not cmi.start_controller('x')
    assert not cmi.reload_libraries(False)
    assert capsys.readouterr().out == (
        "Error when loading 'x'\n"
        "Error when unloading 'x'\n"
        "Error when starting ['x'] and stopping []\n"
        "Restore: False\nFailed to reload libraries. Do you still have controllers loaded?\n")


def test_reload_restore_reloads_and_restarts(monkeypatch, capsys):
    from controller_manager_msgs.msg import ControllerState
    cmi, calls = fake_services(monkeypatch, controllers=[ControllerState(name='a', state='running'),
                                                         ControllerState(name='b', state='stopped')])
    assert cmi.reload_libraries(True, restore=True)
    names = [c[0] for c in calls]
    assert names == ['list_controllers', 'reload_controller_libraries', 'load_controller', 'load_controller',
                     'switch_controller']
    assert calls[-1][2]['start_controllers'] == ['a'] and calls[-1][2]['strictness'] == 1
    assert capsys.readouterr().out.endswith('Controllers restored to original state\n')
