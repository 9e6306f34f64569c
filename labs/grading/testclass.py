"""`make test-class` (labs/test-class.sh): rosters of the lab 1, 2 and 3 references, starters,
seeded faults (the graders' own self-test cases) and the adversarial lab 2 submissions, graded
through labs/grade-class with the local backend and with --backend slurm on a one-node Slurm
brought up here; both gradebooks must be right (references pass, everything else fails, no
errors but the bad rows) and identical (status, score, the verdict of every criterion).

usage: labs/test-class.sh [--labs lab1,lab2,lab3] [--jobs N] [--out DIR] [--keep]
"""
import argparse
import csv
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
import time

from grading import adversarial
from grading.common import LABS_DIR
from grading.selftest import make_repo
from grading.slurm import OneNodeSlurm

GRADE_CLASS = os.path.join(LABS_DIR, 'grade-class')


def self_test_cases(lab):
    """CASES of labs/<lab>/test_<lab>_grader.py: {name: (isu, make_repo kwargs)}."""
    path = os.path.join(LABS_DIR, lab, 'test_%s_grader.py' % lab)
    spec = importlib.util.spec_from_file_location('cases_%s' % lab, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return dict(mod.CASES)


# self-test cases whose nodes compute correctly: what they test is the grader's clean-up
# (lab 1's stubborn_node ignores SIGTERM and leaves a grandchild), so they pass
CORRECT_CASES = {'stubborn_node'}


def roster(lab, root):
    """Write root/<lab>/roster.csv; returns (path, {isu: expected status})."""
    cases = self_test_cases(lab)
    cases.setdefault('starter', ('123456', {'source': 'starter'}))
    if lab == 'lab2':
        cases.update({n: ('123451', kw) for n, kw in adversarial.recipes().items()})
    d = os.path.join(root, lab)
    os.makedirs(d, exist_ok=True)
    rows, expect, n = [], {}, 0
    for name, (isu, kw) in sorted(cases.items()):
        n += 1
        uniq = '%d%02d%s' % (n, n, isu)          # a distinct ISU with the same last digit (variant)
        repo = make_repo(os.path.join(d, name), lab, **kw)
        rows.append((uniq, repo, name))
        expect[uniq] = 'passed' if name.startswith('ref') or name in CORRECT_CASES else 'failed'
    rows.append(('99x1', os.path.join(LABS_DIR, lab, 'reference'), 'bad_isu'))
    expect['99x1'] = 'error'
    rows.append(('9999991', os.path.join(d, 'no-such-repo'), 'missing_repo'))
    expect['9999991'] = 'error'
    path = os.path.join(d, 'roster.csv')
    with open(path, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['isu', 'repo', 'case'])
        w.writerows(rows)
    return path, expect


def grade(lab, rost, out, jobs, backend):
    cmd = [GRADE_CLASS, lab, '--roster', rost, '--jobs', str(jobs), '--out', out, '--backend', backend]
    t = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=6 * 3600)
    print('[test-class] %s %s: exit %d in %.0f s' % (lab, backend, p.returncode, time.monotonic() - t), flush=True)
    if p.returncode != 0:
        print(p.stdout[-3000:])
    with open(os.path.join(out, 'gradebook.csv'), newline='') as f:
        return list(csv.DictReader(f))


def verdicts(rows):
    return {r['isu']: (r['status'], r['score']) + tuple(sorted((k, v.split(':', 1)[0]) for k, v in r.items()
                                                               if k.startswith('c') and k[1:].isdigit()))
            for r in rows}


def main(argv=None):
    ap = argparse.ArgumentParser(prog='labs/test-class.sh')
    ap.add_argument('--labs', default='lab1,lab2,lab3')
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--out')
    ap.add_argument('--keep', action='store_true')
    args = ap.parse_args(argv)
    root = args.out or tempfile.mkdtemp(prefix='test-class-')
    problems = []
    rosters = {lab: roster(lab, os.path.join(root, 'repos')) for lab in args.labs.split(',')}
    local = {lab: grade(lab, r, os.path.join(root, 'local', lab), args.jobs, 'local')
             for lab, (r, _e) in rosters.items()}
    with OneNodeSlurm(os.path.join(root, 'slurm-cluster'), cpus=args.jobs):
        slurm = {lab: grade(lab, r, os.path.join(root, 'slurm', lab), args.jobs, 'slurm')
                 for lab, (r, _e) in rosters.items()}
    for lab, (_r, expect) in rosters.items():
        for name, book in (('local', local[lab]), ('slurm', slurm[lab])):
            got = {r['isu']: r['status'] for r in book}
            for isu, want in expect.items():
                if got.get(isu) != want:
                    case = next((r.get('case') for r in book if r['isu'] == isu), '?')
                    problems.append('%s %s: %s (%s) is %s, expected %s' % (lab, name, isu, case, got.get(isu), want))
        a, b = verdicts(local[lab]), verdicts(slurm[lab])
        for isu in sorted(set(a) | set(b)):
            if a.get(isu) != b.get(isu):
                problems.append('%s: %s differs: local %s, slurm %s' % (lab, isu, a.get(isu), b.get(isu)))
        print('[test-class] %s: %d rows, local and slurm %s' % (lab, len(a), 'identical' if a == b else 'DIFFER'))
    print('[test-class] gradebooks in %s' % root)
    for p in problems:
        print('[test-class] FAIL: ' + p)
    if not problems:
        print('[test-class] OK: every gradebook right, local and slurm identical')
        if not args.keep and not args.out:
            shutil.rmtree(root, ignore_errors=True)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
