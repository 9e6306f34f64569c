"""labs/grade-class: a roster of six lab 2 rows (reference, starter, two adversarial, a missing
repository, a bad ISU) through --jobs 2 gives a gradebook with a correct row for every line; a
second run re-grades nothing."""
import csv
import os
import subprocess

import pytest

from grading import adversarial
from grading.common import LABS_DIR
from grading.selftest import make_repo

GRADE_CLASS = os.path.join(LABS_DIR, 'grade-class')


def git_repo(path):
    """Commit the folder `path` as a git repository; returns its commit id."""
    def git(*a):
        return subprocess.run(['git', '-C', path] + list(a), check=True, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True).stdout.strip()
    git('init', '-q', '-b', 'main')
    git('add', '-A')
    git('-c', 'user.name=Student', '-c', 'user.email=s@example.com', 'commit', '-q', '-m', 'lab 2')
    return git('rev-parse', 'HEAD')


@pytest.fixture(scope='module')
def graded(tmp_path_factory):
    root = tmp_path_factory.mktemp('class')
    recipes = adversarial.recipes()
    kill = make_repo(str(root / 'kill'), 'lab2', **recipes['rosnode_kill'])
    kill_commit = git_repo(kill)
    forge = make_repo(str(root / 'forge'), 'lab2', **recipes['forge_kill'])
    roster = root / 'roster.csv'
    roster.write_text('isu,repo,name\n'
                      '123451,%s,Reference\n'
                      '123456,%s,Starter\n'
                      '223451,%s@main,Killer\n'
                      '323451,%s,Forger\n'
                      '423451,%s,Missing\n'
                      '12a451,%s,Bad ISU\n'
                      % (os.path.join(LABS_DIR, 'lab2', 'reference'), os.path.join(LABS_DIR, 'lab2', 'starter'),
                         kill, forge, str(root / 'no-such-repo'), os.path.join(LABS_DIR, 'lab2', 'reference')))
    out = root / 'out'
    cmd = [GRADE_CLASS, 'lab2', '--roster', str(roster), '--jobs', '2', '--out', str(out)]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
    with open(out / 'gradebook.csv', newline='') as f:
        rows = list(csv.DictReader(f))
    return p, rows, out, cmd, kill_commit


def test_gradebook_has_every_row(graded):
    p, rows, out, _cmd, kill_commit = graded
    assert p.returncode == 0, p.stdout
    assert [r['isu'] for r in rows] == ['123451', '123456', '223451', '323451', '423451', '12a451'], p.stdout
    by = {r['isu']: r for r in rows}
    assert by['123451']['status'] == 'passed' and by['123451']['score'] == '7/7', by['123451']
    assert by['123451']['commit'].startswith('dir:') and by['123451']['name'] == 'Reference'
    st = by['123456']
    assert st['status'] == 'failed' and st['c0'].startswith('pass') and 'turtle 1 never moved' in st['c2'], st
    k = by['223451']
    assert k['status'] == 'failed' and k['commit'] == kill_commit, k
    assert 'tampering: the checker was shut down through the ROS API' in k['c1'], k
    fg = by['323451']
    assert fg['status'] == 'failed' and fg['c0'].startswith('pass') and fg['c1'].startswith('FAIL'), fg
    assert by['423451']['status'] == 'error' and 'does not exist' in by['423451']['c0'], by['423451']
    assert by['12a451']['status'] == 'error' and 'ISU must be digits' in by['12a451']['c0'], by['12a451']
    assert '[grade-class] done 5/5, running 0, left 0' in p.stdout, p.stdout


def test_outputs_per_student(graded):
    p, _rows, out, _cmd, _c = graded
    for isu in ('123451', '123456', '223451', '323451', '423451'):
        for f in ('report.txt', 'junit.xml', 'result.json'):
            assert (out / isu / f).exists(), (isu, f)
    assert 'criteria passed: PASS' in (out / '123451' / 'report.txt').read_text()
    assert (out / '123451' / 'logs' / 'build.log').exists()
    html = (out / 'gradebook.html').read_text()
    assert 'tampering' in html and 'Пакет найден' in html and 'does not exist' in html


def test_second_run_regrades_nothing(graded):
    _p, rows, out, cmd, _c = graded
    logs = {isu: os.path.getmtime(out / isu / 'grade.log') for isu in ('123451', '123456', '223451', '323451')}
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert p.returncode == 0, p.stdout
    assert {isu: os.path.getmtime(out / isu / 'grade.log') for isu in logs} == logs, p.stdout
    with open(out / 'gradebook.csv', newline='') as f:
        again = list(csv.DictReader(f))
    assert again == rows
