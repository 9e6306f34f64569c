"""Lab 2 grader self-tests: the reference passes, seeded faults fail the right criterion."""
import pytest

from grading.selftest import crit, failed, run_cases

NODE = 'src/my_best_controller/node.py'
CASES = {
    'ref_three_points': ('123451', {}),
    # table 10.1 prints row 9 (and 0) as (2,3) (4,2) (7,1) (4,2): the reference visits the
    # three printed points; a route coming back to (4,2) and timed to that arrival passes too
    'ref_row_9_printed': ('334409', {}),
    'row_9_repeat_visited': ('334409', {'edits': [('src/my_best_controller/motion.py',
                                                   'self.todo = route((x, y), self.points)',
                                                   'self.todo = [(2, 3), (4, 2), (7, 1), (4, 2)]')]}),
    'remap_used': ('123451', {'edits': [('launch/lab2_setup.launch',
                                         'name="lab2_controller" output="screen"/>\n  </group>\n</launch>',
                                         'name="lab2_controller" output="screen">\n'
                                         '      <remap from="unused" to="other"/>\n'
                                         '    </node>\n  </group>\n</launch>')]}),
    'point_missed': ('123451', {'edits': [('src/my_best_controller/motion.py',
                                           'self.todo = route((x, y), self.points)',
                                           'self.todo = route((x, y), self.points)[:-1]')]}),
    'global_name': ('123451', {'edits': [(NODE, "rospy.Publisher('result_%s' % isu",
                                          "rospy.Publisher('/result_%s' % isu")]}),
    'not_following': ('123451', {'edits': [(NODE, "leader_ns = ns.replace('ns2_', 'ns1_', 1)", 'leader_ns = ns')]}),
}


@pytest.fixture(scope='module')
def runs(tmp_path_factory):
    return run_cases('lab2', CASES, str(tmp_path_factory.mktemp('lab2')), workers=4)


@pytest.mark.parametrize('name', ['ref_three_points', 'ref_row_9_printed'])
def test_reference_passes(runs, name):
    rc, out, crits = crit(runs, name)
    assert rc == 0, out
    assert sorted(crits) == ['0', '1', '2', '3', '4', '5', '6'] and not failed(crits), out


def test_row_9_printed_points_only(runs):
    _, out, crits = crit(runs, 'ref_row_9_printed')
    assert all(p in crits['2'][1] for p in ('(2,3)', '(4,2)', '(7,1)')) and '(5,4)' not in crits['2'][1], out


def test_row_9_repeated_cell_as_a_second_visit(runs):
    rc, out, crits = crit(runs, 'row_9_repeat_visited')
    assert rc == 0 and not failed(crits), out
    assert 'to the repeated (4,2) again, the row as printed' in crits['3'][1], out


def test_remap_used(runs):
    rc, out, crits = crit(runs, 'remap_used')
    assert rc == 1 and failed(crits) == ['4'], out
    assert 'remap is forbidden' in crits['4'][1] and 'from="unused"' in crits['4'][1]


def test_point_missed(runs):
    rc, out, crits = crit(runs, 'point_missed')
    assert rc == 1 and '2' in failed(crits) and '1' not in failed(crits), out
    assert 'points missed: (' in crits['2'][1]
    assert 'stopped before visiting every point' in crits['6'][1]


def test_global_name(runs):
    rc, out, crits = crit(runs, 'global_name')
    assert rc == 1 and failed(crits) == ['5'], out
    assert 'global name: topic /result_123451' in crits['5'][1]


def test_not_following(runs):
    rc, out, crits = crit(runs, 'not_following')
    assert rc == 1 and failed(crits) == ['4'], out
    assert 'does not subscribe to /ns1_123451/turtle1/pose' in crits['4'][1]


@pytest.mark.full
def test_reference_all_variants(tmp_path):
    cases = {'v%d' % d: ('12345%d' % d, {}) for d in range(10)}
    res = run_cases('lab2', cases, str(tmp_path), workers=2)
    bad = {n: r[1][-2000:] for n, r in res.items() if r[0] != 0}
    assert not bad, bad


@pytest.mark.full
def test_starter_is_not_a_solution(tmp_path):
    res = run_cases('lab2', {'starter': ('123456', {'source': 'starter'})}, str(tmp_path))
    rc, out, crits = res['starter']
    assert rc == 1 and crits['0'][0], out
    assert not crits['1'][0] and 'nobody publishes /ns2_123456/turtle1/pose' in crits['1'][1]
    assert not crits['2'][0] and 'turtle 1 never moved' in crits['2'][1]
