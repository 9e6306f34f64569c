"""Unit tests of lab 1's rules (grading.lab1.rules): no roscore."""
import pytest

from grading.common import GradeError, parse_isu
from grading.lab1 import rules as lab1


def test_isu_and_roles():
    assert parse_isu(' 123456 ') == '123456'
    with pytest.raises(GradeError):
        parse_isu('12a')
    assert lab1.roles('123450') == ('node3', ('node1', 'node2'), '+')
    assert lab1.roles('100009') == ('node1', ('node2', 'node3'), '/')
    assert lab1.roles('100005') == ('node2', ('node1', 'node3'), '+')   # the printed operation


def test_match_results_uses_operand_order_and_window():
    first = [(0.0, 8.0), (1.0, 6.0)]
    second = [(0.5, 2.0)]
    assert lab1.match_results([(1.2, 3.0)], first, second, '/') == (1, 0, None)
    v, wrong, ex = lab1.match_results([(1.2, 1.0 / 3.0)], first, second, '/')
    assert (v, wrong) == (1, 1) and ex[3] == 3.0
    assert lab1.match_results([(0.1, 5.0)], [(0.2, 1.0)], second, '+') == (0, 0, None)   # operands unknown yet
    assert lab1.match_results([(2.0, 3.0)], [(1.0, 7.0)], [(1.0, 2.0)], '/', int_result=True)[1] == 0


def test_match_results_by_causality_not_by_the_checkers_clock():
    """The race of a loaded machine: the computing node got the new operand and published its
    result, but the checker received the result before that operand (separate connections)."""
    first = [(0.0, 2.94), (10.0, 8.94)]      # 8.94 reaches the checker 0.4 s after the result
    second = [(0.0, 7.1)]
    assert lab1.match_results([(9.6, 1.84)], first, second, '-') == (1, 0, None)
    # the computing node still held an operand the checker replaced 8 s before the result
    assert lab1.match_results([(9.0, 2.94 - 7.1)], [(0.0, 2.94), (1.0, 5.0)], second, '-') == (1, 0, None)
    # a slow sender: its only value is a minute old, still the operand in use
    assert lab1.match_results([(70.0, 2.94 - 7.1)], [(0.0, 2.94)], second, '-') == (1, 0, None)
    # a wrong operation stays wrong, reported with the operands the checker had last
    v, wrong, ex = lab1.match_results([(9.6, 2.94 + 7.1)], first, second, '-')
    assert (v, wrong) == (1, 1) and ex[1:] == (2.94, 7.1, 2.94 - 7.1)


def lab1_obs(result_values, comp_pubs=('/result_1234',)):
    # ISU 1234: digit 4 -> node1 computes node2 * node3
    t = [0.5 * i for i in range(12)]
    return {'isu': '1234', 'scripts': ['node1.py', 'node2.py', 'node3.py'], 'not_executable': [],
            'procs': {n: {'rc': None} for n in ('node1', 'node2', 'node3')},
            'nodes': ['/node1', '/node2', '/node3'], 'start': 0.0, 'end': 6.0,
            'pubs': {'/node1': list(comp_pubs), '/node2': ['/a'], '/node3': ['/b']},
            'subs': {'/node1': ['/a', '/b']}, 'types': {'/result_1234': 'std_msgs/Float64'},
            'msgs': {'/a': [(x, 2.0) for x in t], '/b': [(x, 5.0) for x in t],
                     '/result_1234': [(x + 0.1, v) for x, v in zip(t, result_values)]}}


def test_lab1_evaluate_pass_and_failures():
    ok = lab1.evaluate(lab1_obs([10.0] * 12))
    assert [c.passed for c in ok] == [True] * 4, [c.reason for c in ok]
    wrong = lab1.evaluate(lab1_obs([7.0] * 12))
    assert [c.passed for c in wrong] == [True, True, False, True]
    assert 'node2 * node3 = 2 * 5 = 10' in wrong[2].reason['en']
    private = lab1.evaluate(lab1_obs([10.0] * 12, comp_pubs=('/node1/result_1234',)))
    assert private[1].passed is False or private[2].passed is False   # no messages recorded there
    other_ns = lab1.evaluate(lab1_obs([10.0] * 12, comp_pubs=('/x/result_1234',)))
    assert not other_ns[1].passed and 'does not publish' in other_ns[1].reason['en']
    crash = lab1_obs([10.0] * 12)
    crash['procs']['node3'] = {'rc': 1, 'last': 'NameError: x'}
    assert 'node3.py exited with code 1: NameError: x' in lab1.evaluate(crash)[0].reason['en']
    few = lab1_obs([10.0] * 2)
    few['msgs']['/result_1234'] = few['msgs']['/result_1234'][:2]
    assert not lab1.evaluate(few)[3].passed


def lab1_obs_v5(op):
    """ISU 1235: digit 5 -> node2 computes node1 <op> node3; operands 2 and 5."""
    obs = lab1_obs([lab1.apply_op(op, 2.0, 5.0)] * 12)
    obs['isu'] = '1235'
    obs['pubs'] = {'/node2': ['/result_1235'], '/node1': ['/a'], '/node3': ['/b']}
    obs['subs'] = {'/node2': ['/a', '/b']}
    obs['types'] = {'/result_1235': 'std_msgs/Float64'}
    obs['msgs']['/result_1235'] = obs['msgs'].pop('/result_1234')
    return obs


def test_lab1_digit_5_passes_both_readings():
    plus = lab1.evaluate(lab1_obs_v5('+'))
    assert all(c.passed for c in plus), [c.reason['en'] for c in plus]
    assert 'node1 + node3' in plus[2].reason['en'] and 'the reading * passes too' in plus[2].reason['en']
    times = lab1.evaluate(lab1_obs_v5('*'))
    assert all(c.passed for c in times), [c.reason['en'] for c in times]
    assert 'node1 * node3' in times[2].reason['en'] and 'the reading + passes too' in times[2].reason['en']
    minus = lab1.evaluate(lab1_obs_v5('-'))[2]
    assert not minus.passed
    assert 'result -3 but node1 + node3 = 2 + 5 = 7 or node1 * node3 = 2 * 5 = 10' in minus.reason['en']
    # one reading throughout: results alternating + and * are wrong in either reading
    mixed = lab1_obs_v5('+')
    mixed['msgs']['/result_1235'] = [(t, 7.0 if i % 2 else 10.0)
                                     for i, (t, _) in enumerate(mixed['msgs']['/result_1235'])]
    assert not lab1.evaluate(mixed)[2].passed


def test_lab1_digit_4_stays_one_reading():
    wrong = lab1.evaluate(lab1_obs([7.0] * 12))[2]     # digit 4 prints "*" only: "+" fails
    assert not wrong.passed and 'result 7 but node2 * node3 = 2 * 5 = 10 (' in wrong.reason['en']
    assert 'reads two ways' not in wrong.reason['en']


class _Graph:
    """GraphWatcher's surface the observer's rounds use, with no master behind it."""

    def __init__(self):
        self.results = []
        self.nodes = set()
        self.pubs = {}

    def poll(self):
        return True

    def listen(self, topic):
        pass

    def series(self, topic):
        return self.results if topic == '/result_123456' else []


class _Child:
    def __init__(self, rc=None):
        self._rc = rc

    def rc(self):
        return self._rc


def test_observer_stops_waiting_once_a_node_exited_without_a_result():
    """A node that exited is not restarted: AFTER_EXIT s later with no result the observation
    ends instead of waiting out STARTUP_LIMIT; a result that came keeps the normal course."""
    from grading.lab1.observer import Lab1Observer
    obs = Lab1Observer('123456', {}, '/nonexistent')
    obs.graph = _Graph()
    obs.children = {'node1': _Child(), 'node2': _Child(rc=1), 'node3': _Child()}
    assert obs._step(1.0, 0.0, 'node3') is None
    assert obs._step(1.0 + lab1.AFTER_EXIT, 0.0, 'node3') is None
    assert obs._step(1.5 + lab1.AFTER_EXIT, 0.0, 'node3') == 'no result'
    # the same exit after the first result: observed for OBSERVE s as before
    obs = Lab1Observer('123456', {}, '/nonexistent')
    obs.graph = _Graph()
    obs.graph.results = [(0.5, 1.0)]
    obs.children = {'node1': _Child(), 'node2': _Child(rc=1), 'node3': _Child()}
    assert obs._step(1.0, 0.0, 'node3') is None
    assert obs._step(1.0 + lab1.AFTER_EXIT + 1, 0.0, 'node3') == 'observed'
    assert lab1.AFTER_EXIT + 1 >= lab1.OBSERVE


def test_observer_stops_waiting_when_nobody_advertises_the_result():
    """Nodes up, unchanged for SILENT s, and no result topic advertised (the starter's nodes):
    the observation ends; advertised but not yet published: it waits on (STARTUP_LIMIT)."""
    from grading.lab1.observer import Lab1Observer
    obs = Lab1Observer('123456', {}, '/nonexistent')
    obs.graph = _Graph()
    obs.children = {'node1': _Child(), 'node2': _Child(), 'node3': _Child()}
    obs.graph.nodes = {'/node1', '/node2'}
    obs.graph.pubs = {'/node1': {'/number1', '/rosout'}, '/node2': {'/number2'}}
    assert obs._step(1.0, 0.0, 'node3') is None
    obs.graph.nodes.add('/node3')               # a node more: the wait starts again
    assert obs._step(1.0 + lab1.SILENT, 0.0, 'node3') is None
    assert obs._step(1.0 + 2 * lab1.SILENT, 0.0, 'node3') is None
    assert obs._step(2.0 + 2 * lab1.SILENT, 0.0, 'node3') == 'no result'
    obs = Lab1Observer('123456', {}, '/nonexistent')
    obs.graph = _Graph()
    obs.children = {'node1': _Child(), 'node2': _Child(), 'node3': _Child()}
    obs.graph.nodes = {'/node1', '/node2', '/node3'}
    obs.graph.pubs = {'/node3': {'/result_123456'}}
    assert obs._step(1.0, 0.0, 'node3') is None
    assert obs._step(lab1.STARTUP_LIMIT - 1, 0.0, 'node3') is None
    assert obs._step(lab1.STARTUP_LIMIT + 1, 0.0, 'node3') == 'no result'
