"""Lab 1 grader self-tests: the reference passes, seeded faults fail the right criterion."""
import os

import pytest

from grading.selftest import crit, failed, run_cases

STUBBORN = '''    import signal, subprocess, time
    subprocess.Popen(['setsid', 'sleep', '6001'])
    main(2)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    while True:
        time.sleep(1)
'''

CASES = {
    # name: (ISU, faults seeded into a copy of the reference)
    'ref_minus_node3': ('123456', {}),
    'ref_div_node1': ('334409', {}),
    'wrong_operation': ('123456', {'edits': [('src/my_robot_controller/numbers.py', "'-': a - b", "'-': b - a")]}),
    'wrong_topic': ('123456', {'edits': [('src/my_robot_controller/numbers.py',
                                          "'result_%s' % isu", "'result%s' % isu")]}),
    'four_nodes': ('123456', {'add': {'scripts/node4.py': '#!/usr/bin/env python3\nimport rospy\n'
                                                          'rospy.init_node("node4")\nrospy.spin()\n'}}),
    'node_crashes': ('123456', {'edits': [('scripts/node2.py', 'from my_robot_controller',
                                           'raise RuntimeError("boom")\nfrom my_robot_controller')]}),
    'cmake_syntax': ('123456', {'edits': [('CMakeLists.txt', 'catkin_package()', 'catkin_package(')]}),
    'missing_dependency': ('123456', {'edits': [('CMakeLists.txt', 'rospy std_msgs)',
                                                 'rospy std_msgs no_such_pkg_xyz)')]}),
    'starter': ('123456', {'source': 'starter'}),
    # a node that ignores SIGINT/SIGTERM once rospy shut down and leaves a grandchild in a
    # session of its own: the grade still ends and nothing of it survives
    'stubborn_node': ('123456', {'edits': [('scripts/node2.py', '    main(2)\n', STUBBORN)]}),
    'wrong_package_name': ('123456', {'edits': [('package.xml', '<name>my_robot_controller<',
                                                 '<name>my_robot_controler<')]}),
    # table 9.1 prints "+" for digit 5 (the reference follows the page); "*" is read there too
    'v5_printed_plus': ('123455', {}),
    'v5_read_as_times': ('123455', {'edits': [('src/my_robot_controller/numbers.py', "5: (2, '+')", "5: (2, '*')")]}),
    # an instructor's table (--variants) where digit 5 is "*" only: the printed "+" now fails
    'v5_table_times_only': ('123455', {}),
}
TIMES_ONLY = 'variants:\n' + ''.join("  %d: {operation: '%s', compute: node%d}\n" % (d, op, n) for d, op, n in zip(
    range(10), '+++***---/', (3, 1, 2, 3, 1, 2, 3, 1, 2, 1)))


@pytest.fixture(scope='module')
def runs(tmp_path_factory):
    root = tmp_path_factory.mktemp('lab1')
    (root / 'times_only.yaml').write_text(TIMES_ONLY)
    cases = dict(CASES, v5_table_times_only=('123455', {'args': ['--variants', str(root / 'times_only.yaml')]}))
    return run_cases('lab1', cases, str(root / 'runs'), workers=4)


@pytest.mark.parametrize('name', ['ref_minus_node3', 'ref_div_node1'])
def test_reference_passes(runs, name):
    rc, out, crits = crit(runs, name)
    assert rc == 0, out
    assert sorted(crits) == ['0', '1', '2', '3', '4'] and all(p for p, _ in crits.values()), out


@pytest.mark.parametrize('name,formula', [('v5_printed_plus', 'node1 + node3'), ('v5_read_as_times', 'node1 * node3')])
def test_digit_5_either_reading_passes(runs, name, formula):
    rc, out, crits = crit(runs, name)
    assert rc == 0 and not failed(crits), out
    assert formula in crits['3'][1], out


def test_variants_file_is_used(runs):
    rc, out, crits = crit(runs, 'v5_table_times_only')
    assert rc == 1 and failed(crits) == ['3'], out
    assert 'but node1 * node3 = ' in crits['3'][1] and 'reads two ways' not in crits['3'][1], out
    assert 'variant table: ' in out and 'times_only.yaml (--variants)' in out


def test_wrong_operation(runs):
    rc, out, crits = crit(runs, 'wrong_operation')
    assert rc == 1 and failed(crits) == ['3'], out
    assert 'node1 - node2' in crits['3'][1] and 'wrong' in crits['3'][1]


def test_wrong_topic(runs):
    rc, out, crits = crit(runs, 'wrong_topic')
    assert rc == 1 and '2' in failed(crits) and '1' not in failed(crits), out
    assert 'does not publish /result_123456' in crits['2'][1]


def test_four_nodes(runs):
    rc, out, crits = crit(runs, 'four_nodes')
    assert rc == 1 and failed(crits) == ['1'], out
    assert 'extra node scripts' in crits['1'][1] and 'node4.py' in crits['1'][1]


def test_node_crashes(runs):
    rc, out, crits = crit(runs, 'node_crashes')
    assert rc == 1 and '1' in failed(crits), out
    assert 'node2.py exited with code 1' in crits['1'][1] and 'boom' in crits['1'][1]


@pytest.mark.parametrize('name,words', [('cmake_syntax', 'does not build'),
                                        ('missing_dependency', 'find_package(no_such_pkg_xyz)')])
def test_build_failure(runs, name, words):
    rc, out, crits = crit(runs, name)
    assert rc == 1 and failed(crits) == ['0', '1', '2', '3', '4'], out
    assert words in crits['0'][1]
    assert crits['1'][1].startswith('not checked')


def test_wrong_package_name(runs):
    rc, out, crits = crit(runs, 'wrong_package_name')
    assert rc == 1 and failed(crits) == ['0', '1', '2', '3', '4'], out
    assert 'package my_robot_controller not found in' in crits['0'][1]
    assert '(found: my_robot_controler)' in crits['0'][1]


def test_starter_is_not_a_solution(runs):
    rc, out, crits = crit(runs, 'starter')
    assert rc == 1 and crits['0'][0], out
    assert 'extra node scripts in the package (exactly three wanted): node4.py, node5.py' in crits['1'][1]
    assert 'does not publish /result_123456' in crits['2'][1]


def _cmdline(pid):
    try:
        with open('/proc/%s/cmdline' % pid, 'rb') as f:
            return f.read()
    except OSError:
        return b''


def test_stubborn_node_is_killed_with_its_tree(runs):
    rc, out, crits = crit(runs, 'stubborn_node')
    assert rc == 0, out     # it works while running; stopping it is the grader's job
    left = [pid for pid in os.listdir('/proc') if pid.isdigit() and _cmdline(pid) == b'sleep\x006001\x00']
    assert not left, 'processes of the graded run survived the grader: %s' % left


@pytest.mark.full
def test_reference_all_variants(tmp_path):
    cases = {'v%d' % d: ('12345%d' % d, {}) for d in range(10)}
    res = run_cases('lab1', cases, str(tmp_path), workers=3)
    bad = {n: r[1][-1500:] for n, r in res.items() if r[0] != 0}
    assert not bad, bad
