"""controller_group's logic without a master (a fake controller manager)."""
from collections import namedtuple

from controller_manager import group

C = namedtuple('C', 'name state')
GROUPS = {'drive': ['vel', 'state'], 'arm': ['arm_pos', 'state'], 'empty': []}


class FakeCM(object):
    def __init__(self, loaded=None, fail_load=()):
        self.loaded = dict(loaded or {})        # name -> state
        self.fail_load = set(fail_load)
        self.calls = []

    def list(self):
        return [C(n, s) for n, s in self.loaded.items()]

    def load(self, name):
        self.calls.append(('load', name))
        if name in self.fail_load:
            return False
        self.loaded.setdefault(name, 'initialized')
        return True

    def start(self, name):
        self.calls.append(('start', name))
        self.loaded[name] = 'running'
        return True

    def start_stop(self, start, stop):
        self.calls.append(('switch', list(start), list(stop)))
        for n in stop:
            self.loaded[n] = 'stopped'
        for n in start:
            self.loaded[n] = 'running'
        return True


def test_list_prints_groups_sorted_with_their_controllers():
    lines = []
    group.list_groups(GROUPS, out=lines.append)
    assert lines == ['Number of groups: 3', '  arm', '      arm_pos', '      state', '  drive',
                     '      vel', '      state', '  empty']
    lines = []
    group.list_groups('not a dict', out=lines.append)
    assert lines == ['Number of groups: 0']


def test_spawn_loads_then_starts_the_group():
    cm = FakeCM()
    assert group.spawn_group(GROUPS, 'drive', cm, logerr=None)
    assert cm.calls == [('load', 'state'), ('load', 'vel'), ('start', 'state'), ('start', 'vel')]


def test_empty_or_unknown_group_is_an_error_line():
    errors = []
    cm = FakeCM()
    assert not group.spawn_group(GROUPS, 'empty', cm, errors.append)
    assert not group.switch_group(GROUPS, 'nope', cm, errors.append)
    assert errors == ['There is no controller defined in group empty',
                      'There is no controller defined in group nope']
    assert cm.calls == []


def test_switch_stops_the_other_groups_and_starts_this_one_in_one_switch():
    cm = FakeCM({'vel': 'running', 'state': 'running'})
    assert group.switch_group(GROUPS, 'arm', cm, logerr=None)
    assert cm.calls == [('load', 'arm_pos'), ('switch', ['arm_pos'], ['vel'])]
    assert cm.loaded == {'vel': 'stopped', 'state': 'running', 'arm_pos': 'running'}


def test_switch_cancels_when_a_controller_cannot_load():
    out = []
    cm = FakeCM({'vel': 'running'}, fail_load={'arm_pos'})
    assert not group.switch_group(GROUPS, 'arm', cm, logerr=None, out=out.append)
    assert out == ['Cancel group switching']
    assert ('switch', ['arm_pos'], ['vel']) not in cm.calls and cm.loaded['vel'] == 'running'


def test_unknown_states_are_reported_and_not_running():
    errors = []
    states = group.loaded_controllers(FakeCM({'a': 'running', 'b': 'initialized'}), errors.append)
    assert states == {'a': True, 'b': False}
    assert errors == ['Unknown controller state initialized']


def test_parser_commands():
    p = group.parser()
    assert p.parse_args(['switch', 'arm']).group == 'arm'
    assert p.parse_args(['list']).command == 'list'
