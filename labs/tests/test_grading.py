"""Unit tests of the graders' core (variant tables, report, workspace; no roscore) and of the
CLI's bad-input handling; each lab's rules are tested beside the lab (labs/labN/test_labN_*.py)."""
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest

from grading.common import Criterion, GradeError, reason
from grading.lab1 import rules as lab1
from grading.lab2 import variants as lab2
from grading.labs import load_variants
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
    assert ('\u2714 1. а / first' in text and '\u2718 2. б / second thing' in text
            and '1/2 criteria passed: FAIL' in text)
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


VALID_LAB1 = 'variants:\n' + ''.join("  %d: {operation: '+', compute: node1}\n" % d for d in range(10))


@pytest.mark.parametrize('text,words', [
    ('variants: [1, 2', 'not YAML at line'),
    ('rows: {}', 'no "variants:" mapping'),
    (VALID_LAB1.replace('  7: {', '  x7: {'), "key 'x7' is not a digit 0-9"),
    (VALID_LAB1.replace("  3: {operation: '+'", "  3: {operation: '%'"),
     "digit 3: operation '%' is not one of + - * /"),
    (VALID_LAB1.replace("  3: {operation: '+'", "  3: {operaton: '+'"), "digit 3: unknown field 'operaton'"),
    (VALID_LAB1.replace('compute: node1}\n  4', 'compute: node4}\n  4'), "digit 3: compute 'node4' is not node1"),
    (VALID_LAB1.replace("  9: {operation: '+', compute: node1}\n", ''),
     'no row for digit 9 (a lab1 table needs all ten)'),
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
        assert (p.stderr.strip().count('\n') == 0 and words in p.stderr
                and 'variants file %s' % (tmp_path / f) in p.stderr)


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
    assert ('no row for digit' in p.stderr and 'a lab2 table needs all ten' in p.stderr
            and not (tmp_path / 'out').exists())
