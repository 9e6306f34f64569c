"""Helpers of the graders' self-tests: seeded faulty copies of a reference, parallel runs."""
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET
from concurrent.futures import ThreadPoolExecutor

from grading.common import LABS_DIR

GRADE = os.path.join(LABS_DIR, 'grade')


def make_repo(root, lab, edits=(), add=None, source='reference'):
    """Copy labs/<lab>/<source> into root/repo and apply edits [(relpath, old, new)];
    add = {relpath: text}; returns the repo path."""
    repo = os.path.join(root, 'repo')
    shutil.copytree(os.path.join(LABS_DIR, lab, source), repo)
    pkg = os.path.join(repo, os.listdir(repo)[0])
    for rel, old, new in edits:
        p = os.path.join(pkg, rel)
        with open(p) as f:
            text = f.read()
        if old not in text:
            raise AssertionError('seeding a fault: %r not found in %s' % (old, rel))
        with open(p, 'w') as f:
            f.write(text.replace(old, new, 1))
    for rel, text in (add or {}).items():
        p = os.path.join(pkg, rel)
        with open(p, 'w') as f:
            f.write(text)
        os.chmod(p, 0o755)
    return repo


def run_grade(lab, isu, repo, workdir, timeout=None, args=()):
    """Run labs/grade like a student; returns (exit code, stdout, {id: (passed, en reason)})."""
    junit = os.path.join(workdir, 'report.xml')
    cmd = [GRADE, lab, '--isu', isu, '--repo', repo, '--junit', junit] + list(args)
    if timeout:
        cmd += ['--timeout', str(timeout)]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
    crits = {}
    if os.path.exists(junit):
        for case in ET.parse(junit).getroot().iter('testcase'):
            cid = case.get('name').split('_')[0]
            f = case.find('failure')
            crits[cid] = (f is None, f.get('message') if f is not None else case.findtext('system-out'))
    return p.returncode, p.stdout, crits


def run_cases(lab, cases, root, workers=2, args=()):
    """cases: {name: (isu, make_repo kwargs)} -> {name: run_grade result}, run in parallel;
    `args`: more labs/grade options (e.g. --no-sandbox) for every case; a case's own options
    go in its kwargs as 'args'."""
    def one(item):
        name, (isu, kw) = item
        kw = dict(kw)
        more = list(kw.pop('args', ()))
        d = os.path.join(root, name)
        os.makedirs(d)
        repo = make_repo(d, lab, **kw)
        return name, run_grade(lab, isu, repo, d, args=list(args) + more)
    with ThreadPoolExecutor(workers) as ex:
        return dict(ex.map(one, sorted(cases.items())))


def crit(runs, name):
    """(exit code, output, {id: (passed, reason)}) of the case `name`; fails when the grade
    produced no report at all."""
    rc, out, crits = runs[name]
    assert crits, out
    return rc, out, crits


def failed(crits):
    """Ids of the criteria that failed, sorted."""
    return sorted(c for c, (p, _) in crits.items() if not p)
