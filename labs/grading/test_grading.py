"""Unit tests of the graders' pure logic (no roscore) and of the CLI's bad-input handling."""
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest

from grading import lab2
from grading.lab1 import rules as lab1
from grading.common import Criterion, GradeError, load_variants, reason
from grading.report import format_report, write_junit
from grading.workspace import build_error, find_packages

GRADE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'grade')


def test_variant_tables_cover_every_digit():
    v1, v2 = load_variants('lab1'), load_variants('lab2')
    assert sorted(v1) == sorted(v2) == list(range(10))
    # table 9.1 as printed: digit 5 prints "+", and "*" (the rows' pattern) passes too
    assert [v1[d]['operation'] for d in range(10)] == ['+', '+', '+', '*', '*', ['+', '*'], '-', '-', '-', '/']
    assert [v1[d]['compute'] for d in range(10)] == ['node3', 'node1', 'node2'] * 3 + ['node1']
    # table 10.1 as printed: rows 9 and 0 repeat (4,2), rows 7 and 8 repeat (5,4)
    assert v2[0]['points'] == v2[9]['points'] == [[2, 3], [4, 2], [7, 1], [4, 2]]
    assert v2[7]['points'] == [[2, 3], [5, 4], [5, 4]] and v2[8]['points'] == [[7, 1], [5, 4], [5, 4]]
    assert lab2.points('19') == [(2.0, 3.0), (4.0, 2.0), (7.0, 1.0)]
    assert lab1.operations('15') == ('+', '*') and lab1.operations('13') == ('*',)


def test_reference_tables_match_variants():
    import importlib.util
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    spec = importlib.util.spec_from_file_location(
        'motion', os.path.join(here, 'lab2/reference/my_best_controller/src/my_best_controller/motion.py'))
    motion = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(motion)
    assert {d: lab2.points(str(d)) for d in range(10)} == motion.POINTS   # the distinct printed points


def path(points, t0=0.0, dt=0.1, step=0.05):
    out, t = [], t0
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        n = max(1, int(((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5 / step))
        for k in range(n):
            out.append((t, x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n, 0.0))
            t += dt
    out.append((t, points[-1][0], points[-1][1], 0.0))
    return out


def test_path_geometry():
    a = path([(5.5, 5.5), (4, 2), (2, 3)])
    b = path([(5.5, 5.5), (4.2, 2.1), (2, 3)])
    assert lab2.path_deviation(a, a) < 0.06
    assert 0.15 < lab2.path_deviation(a, b) < 0.3
    v = lab2.visits(a, [(4, 2), (7, 1)], 0.3)
    assert v[(4, 2)][0] < 0.05 and v[(7, 1)][1] is None and v[(7, 1)][0] > 2
    assert lab2.first_motion([(0, 1, 1, 0), (1, 1, 1, 0.2)]) == 1
    assert lab2.wall_hits([(0, 0.0, 5, 0), (1, 5, 5, 0)]) == [(0, 0.0, 5, 0)]


def lab2_obs(p2_shift=0.0, isu='7772', route=((4, 2), (2, 3)), reported=None):
    """Turtle 1 drives `route` from the centre; turtle 2 the same (its first point shifted
    by p2_shift in x). ISU 7772: points (2,3) (4,2). The time published is `reported`, or
    0.3 s more than the time to the last point."""
    ns1, ns2 = '/ns1_' + isu, '/ns2_' + isu
    p1 = [(0.0, 5.544, 5.544, 0.0)] + path([(5.544, 5.544)] + list(route), t0=1.0)
    shifted = [(route[0][0] + p2_shift, route[0][1])] + list(route[1:])
    p2 = [(0.0, 5.544, 5.544, 0.0)] + path([(5.544, 5.544)] + shifted, t0=2.0)
    if reported is None:
        last = route[-1]
        reported = next(t for t, x, y, _ in p1 if abs(x - last[0]) < 0.3 and abs(y - last[1]) < 0.3) - p1[1][0] + 0.3
    n1, n2 = ns1 + '/c', ns2 + '/c'
    return {'isu': isu, 'remaps': [], 'global_literals': [], 'end_reason': 'still', 'duration': 30.0,
            'pose1': p1, 'pose2': p2, 'wall_msgs': [],
            'results': {ns1 + '/result_' + isu: [(50.0, reported)]},
            'nodes': [ns1 + '/sim', ns2 + '/sim', n1, n2],
            'pubs': {ns1 + '/sim': [ns1 + '/turtle1/pose', '/rosout'], ns2 + '/sim': [ns2 + '/turtle1/pose'],
                     n1: [ns1 + '/turtle1/cmd_vel', ns1 + '/result_' + isu], n2: [ns2 + '/turtle1/cmd_vel']},
            'subs': {n1: [ns1 + '/turtle1/pose'], n2: [ns2 + '/turtle1/pose', ns1 + '/turtle1/pose']},
            'srvs': {ns1 + '/sim': [ns1 + '/spawn']}}


def test_lab2_evaluate():
    ok = lab2.evaluate(lab2_obs())
    assert all(c.passed for c in ok), [c.reason['en'] for c in ok]
    off = lab2.evaluate(lab2_obs(p2_shift=1.0))
    assert not off[3].passed and 'paths differ' in off[3].reason['en']
    g = lab2_obs()
    g['pubs']['/ns1_7772/c'].append('/turtle1/cmd_vel')
    assert 'global name: topic /turtle1/cmd_vel' in lab2.evaluate(g)[4].reason['en']
    late = lab2_obs()
    late['results']['/ns1_7772/result_7772'] = [(50.0, 99.0)]
    assert 'measured' in lab2.evaluate(late)[2].reason['en'] and not lab2.evaluate(late)[2].passed
    noluanch = {'isu': '7772', 'launch_error': 'launch/lab2_setup.launch not found in package my_best_controller',
                'end_reason': 'launch_exited'}
    res = lab2.evaluate(noluanch)
    assert not any(c.passed for c in res) and 'not found' in res[0].reason['en']


def test_lab2_static_checks(tmp_path):
    pkg = tmp_path / 'p'
    (pkg / 'launch').mkdir(parents=True)
    (pkg / 'scripts').mkdir()
    (pkg / 'launch' / 'lab2_setup.launch').write_text(
        '<launch><arg name="isu" default="1"/><group ns="a"><node pkg="x" type="y" name="n" args="in:=out _p:=1">'
        '<remap from="a" to="b"/></node></group></launch>')
    (pkg / 'scripts' / 'c.py').write_text('"""/doc/string"""\nimport rospy\nrospy.Subscriber("/turtle1/pose", None)\n'
                                          'rospy.Publisher("cmd_vel", None)\nopen("/tmp/x")\n')
    assert lab2.declares_isu(lab2.find_launch(str(pkg)))
    r = lab2.remaps(str(pkg))
    assert len(r) == 2 and 'from="a" to="b"' in r[0] and 'in:=out' in r[1]
    assert lab2.global_literals(str(pkg)) == ['scripts/c.py:3 "/turtle1/pose"']


def test_find_packages_and_build_error(tmp_path):
    for name, d in (('a_pkg', 'x/a'), ('b_pkg', 'y/b'), ('c_pkg', 'build/c')):
        (tmp_path / d).mkdir(parents=True)
        (tmp_path / d / 'package.xml').write_text('<package><name>%s</name></package>' % name)
    assert sorted(find_packages(str(tmp_path))) == ['a_pkg', 'b_pkg']
    log = 'x\nCMake Warning at foo\nCould not find a package configuration file provided by "foo_msgs" with\n'
    assert build_error(log) == 'missing dependency: find_package(foo_msgs) failed (no such package)'
    log = 'CMake Error at CMakeLists.txt:5:\n  Parse error.  Function missing ending ")".\n'
    assert build_error(log).startswith('CMake Error at CMakeLists.txt:5: Parse error')


def test_report_and_junit(tmp_path):
    crits = [Criterion('1', 'а', 'first', True, reason('ок', 'fine')),
             Criterion('2', 'б', 'second thing', False, reason('плохо', 'bad'))]
    text = format_report('lab1', '123', crits)
    assert '\u2714 1. а / first' in text and '\u2718 2. б / second thing' in text and '1/2 criteria passed: FAIL' in text
    out = tmp_path / 'j.xml'
    write_junit(str(out), 'lab1', '123', crits)
    cases = list(ET.parse(out).getroot().iter('testcase'))
    assert [c.get('name') for c in cases] == ['1_first', '2_second_thing']
    assert cases[1].find('failure').get('message') == 'bad' and cases[0].find('failure') is None


@pytest.mark.parametrize('args,words', [
    (['lab7', '--isu', '1'], "unknown lab 'lab7'"),
    (['lab1', '--isu', '12x'], 'ISU id must be digits'),
    (['lab1', '--isu', '1', '--repo', '/nonexistent/repo'], 'repository folder /nonexistent/repo does not exist'),
    (['lab1', '--isu', '1', '--timeout', '-5'], '--timeout must be positive'),
])
def test_cli_bad_input_one_line(args, words, tmp_path):
    p = subprocess.run([GRADE] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       timeout=60, cwd=str(tmp_path))
    assert p.returncode == 2
    assert p.stderr.strip().count('\n') == 0 and words in p.stderr and 'Traceback' not in p.stderr


# --- the variant tables as printed (issue 29 §3) --------------------------------------------


def lab2_obs_v9(route, reported_at):
    """ISU 7779 (row (2,3) (4,2) (7,1) (4,2)): turtle 1 drives `route`; the time published is
    that of its arrival at the end of leg `reported_at`, from the first motion."""
    p1 = [(0.0, 5.544, 5.544, 0.0)] + path([(5.544, 5.544)] + list(route), t0=1.0)
    ends, i = [], 1
    for q in route:       # path() puts each leg's end point exactly, in order
        while not (p1[i][1] == q[0] and p1[i][2] == q[1]):
            i += 1
        ends.append(p1[i][0])
        i += 1
    return lab2_obs(isu='7779', route=route, reported=ends[reported_at] - p1[1][0])


def test_lab2_row_9_as_printed():
    # the distinct printed points, time to the last of them: passes; (5,4) is not asked for
    once = lab2.evaluate(lab2_obs_v9([(4, 2), (2, 3), (7, 1)], 2))
    assert all(c.passed for c in once), [c.reason['en'] for c in once]
    assert 'visited (tolerance 0.3 m): (4,2)' in once[1].reason['en'] and '(5,4)' not in once[1].reason['en']
    # the repeated cell read as one more visit: back to (4,2), time to that arrival: passes
    again = lab2.evaluate(lab2_obs_v9([(2, 3), (4, 2), (7, 1), (4, 2)], 3))
    assert all(c.passed for c in again), [c.reason['en'] for c in again]
    assert 'to the repeated (4,2) again, the row as printed' in again[2].reason['en']
    # the same route, but the time of the first (7,1) arrival: passes too (first reading)
    assert lab2.evaluate(lab2_obs_v9([(2, 3), (4, 2), (7, 1), (4, 2)], 2))[2].passed
    # a time to neither: fails, naming both
    wrong = lab2.evaluate(lab2_obs_v9([(2, 3), (4, 2), (7, 1), (4, 2)], 0))[2]
    assert not wrong.passed and 'or ' in wrong.reason['en'] and 'to the repeated (4,2) again' in wrong.reason['en']
    # a row without a repeat has one reading: a later revisit does not change the time
    p = path([(5.5, 5.5), (4, 2), (2, 3), (4, 2)])
    v = lab2.visits(p, [(4.0, 2.0), (2.0, 3.0)], 0.3)
    assert lab2.row_time(p, [(4.0, 2.0), (2.0, 3.0)], 0.3) == v[(2.0, 3.0)][1] == max(w for _, w in v.values())


def test_lab2_arrivals_need_leaving():
    p = path([(5.5, 5.5), (4, 2), (4.2, 2.1), (4, 2), (2, 3), (4, 2)])
    times = lab2.arrivals(p, (4.0, 2.0), 0.3)
    assert len(times) == 2     # dithering within 0.6 m is one arrival; coming back from (2,3) is another
    assert lab2.row_time(p, [(4.0, 2.0), (2.0, 3.0), (4.0, 2.0)], 0.3) == times[1]
    assert lab2.row_time(p, [(4.0, 2.0)] * 3, 0.3) is None


VALID_LAB1 = 'variants:\n' + ''.join("  %d: {operation: '+', compute: node1}\n" % d for d in range(10))


@pytest.mark.parametrize('text,words', [
    ('variants: [1, 2', 'not YAML at line'),
    ('rows: {}', 'no "variants:" mapping'),
    (VALID_LAB1.replace('  7: {', '  x7: {'), "key 'x7' is not a digit 0-9"),
    (VALID_LAB1.replace("  3: {operation: '+'", "  3: {operation: '%'"), "digit 3: operation '%' is not one of + - * /"),
    (VALID_LAB1.replace("  3: {operation: '+'", "  3: {operaton: '+'"), "digit 3: unknown field 'operaton'"),
    (VALID_LAB1.replace('compute: node1}\n  4', 'compute: node4}\n  4'), "digit 3: compute 'node4' is not node1"),
    (VALID_LAB1.replace("  9: {operation: '+', compute: node1}\n", ''), 'no row for digit 9 (a lab1 table needs all ten)'),
])
def test_bad_variants_file_is_one_line(tmp_path, text, words):
    f = tmp_path / 'v.yaml'
    f.write_text(text)
    with pytest.raises(GradeError) as e:
        load_variants('lab1', str(f))
    assert words in str(e.value) and str(f) in str(e.value) and '\n' not in str(e.value)


@pytest.mark.parametrize('lab,row,words', [
    ('lab2', '{points: [[2, 3], [12, 1]]}', 'point [12, 1] lies outside'),
    ('lab2', '{points: []}', 'points [] is not a list of [x, y] pairs'),
    ('lab3', '{links: 0, arm: RR, wheels: CC, body: [1, 2, 3]}', 'links 0 is not a positive'),
    ('lab3', '{links: 5, arm: RX, wheels: CC, body: [1, 2, 3]}', "arm 'RX' is not a string of R, P, C"),
    ('lab3', '{links: 5, arm: RR, wheels: CC, body: [1, 2]}', 'body [1, 2] is not [L, W, H]'),
    ('lab4', '{lidar: [3.0, 0.03], camera: [640, 480], body: [1, 2, 3]}', 'lidar [3.0, 0.03] is not'),
    ('lab4', '{lidar: [0.03, 3.0], camera: [640.5, 480], body: [1, 2, 3]}', 'camera [640.5, 480] is not'),
])
def test_bad_rows_of_other_labs(tmp_path, lab, row, words):
    f = tmp_path / 'v.yaml'
    f.write_text('variants:\n' + ''.join('  %d: %s\n' % (d, row) for d in range(10)))
    with pytest.raises(GradeError) as e:
        load_variants(lab, str(f))
    assert 'digit 0: ' + words in str(e.value)


def test_shipped_tables_validate_and_env_selects_a_table(tmp_path, monkeypatch):
    for lab in ('lab1', 'lab2', 'lab3', 'lab4'):
        assert sorted(load_variants(lab)) == list(range(10))
    f = tmp_path / 'v.yaml'
    f.write_text(VALID_LAB1.replace("  5: {operation: '+', compute: node1}", "  5: {operation: '*', compute: node3}"))
    monkeypatch.setenv('GRADING_VARIANTS', str(f))
    assert lab1.roles('1235') == ('node3', ('node1', 'node2'), '*') and lab1.operations('1235') == ('*',)


def run_grade_cli(args, cwd):
    return subprocess.run([GRADE] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          timeout=120, cwd=str(cwd))


def test_cli_bad_variants_file(tmp_path):
    (tmp_path / 'v.yaml').write_text(VALID_LAB1.replace("  9: {operation: '+', compute: node1}\n", ''))
    for f, words in (('v.yaml', 'no row for digit 9'), ('missing.yaml', 'cannot read it')):
        p = run_grade_cli(['lab1', '--isu', '1', '--repo', str(tmp_path), '--variants', f], tmp_path)
        assert p.returncode == 2 and 'Traceback' not in p.stderr, p.stderr
        assert p.stderr.strip().count('\n') == 0 and words in p.stderr and 'variants file %s' % (tmp_path / f) in p.stderr


def test_cli_writes_junit_only_where_asked(tmp_path):
    """A bare run leaves nothing in the current folder; --junit writes there; --variants is
    recorded in the report. (An empty repository: the grade ends at the package criterion.)"""
    repo = tmp_path / 'repo'
    repo.mkdir()
    cwd = tmp_path / 'cwd'
    cwd.mkdir()
    p = run_grade_cli(['lab1', '--isu', '123455', '--repo', str(repo), '--no-sandbox'], cwd)
    assert p.returncode == 1 and 'package my_robot_controller not found' in p.stdout, p.stdout + p.stderr
    assert os.listdir(str(cwd)) == [] and 'JUnit' not in p.stdout
    (cwd / 'v.yaml').write_text(VALID_LAB1)
    p = run_grade_cli(['lab1', '--isu', '123455', '--repo', str(repo), '--no-sandbox', '--junit', 'out/j.xml',
                       '--variants', 'v.yaml'], cwd)
    assert p.returncode == 1 and 'variant table: %s (--variants)' % (cwd / 'v.yaml') in p.stdout, p.stdout + p.stderr
    suite = ET.parse(str(cwd / 'out' / 'j.xml')).getroot().find('testsuite')
    props = {e.get('name'): e.get('value') for e in suite.iter('property')}
    assert props['variants'] == str(cwd / 'v.yaml') and sorted(os.listdir(str(cwd))) == ['out', 'v.yaml']


def test_grade_class_checks_variants_first(tmp_path):
    (tmp_path / 'roster.csv').write_text('isu,repo\n123451,%s\n' % tmp_path)
    (tmp_path / 'v.yaml').write_text('variants:\n  1: {points: [[2, 3]]}\n')
    p = subprocess.run([os.path.join(os.path.dirname(GRADE), 'grade-class'), 'lab2', '--roster', 'roster.csv',
                        '--variants', 'v.yaml', '--no-sandbox', '--out', 'out'],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60, cwd=str(tmp_path))
    assert p.returncode == 2 and p.stderr.strip().count('\n') == 0, p.stderr
    assert 'no row for digit' in p.stderr and 'a lab2 table needs all ten' in p.stderr and not (tmp_path / 'out').exists()
