"""labs/grade-class LAB --roster FILE [--jobs N] [--out DIR] [--backend local|slurm]
[--deadline DATE] [--force] [--no-sandbox] [--timeout S]

Grades every row of a roster (CSV with the columns `isu,repo`; more columns are kept): fetches
the repository at its ref (or the last commit before --deadline), runs `labs/grade` on it in its
own sandbox (its own master, ROS_HOME and logs), N rows at a time, and writes DIR/gradebook.csv,
DIR/gradebook.html and DIR/<isu>/{report.txt,junit.xml,grade.log,logs/}. Rows already graded at
the same commit are kept (--force re-grades all), so an interrupted run resumes.
"""
import argparse
import csv
import hashlib
import html
import json
import os
import re
import shutil
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import course_runtime

from grading import sandbox, slurm
from grading.common import LABS_DIR, Criterion, GradeError, reason
from grading.labs import LABS, load_variants
from grading.report import format_report, write_junit

GRADE = os.path.join(LABS_DIR, 'grade')
FETCH_TIMEOUT = 180.0
BUILD_AND_SLACK = 420.0     # on top of the lab's checker time limit: the build and start-up
RESULT = 'result.json'


class RosterError(Exception):
    pass


def criteria_of(lab):
    return [('0', 'Пакет найден и собирается', 'Package found and builds')] + list(LABS[lab].CRITERIA)


def read_roster(path):
    """[(line number, row dict)], the extra column names."""
    try:
        with open(path, newline='') as f:
            rd = csv.DictReader(f)
            cols = [c.strip() for c in (rd.fieldnames or [])]
            if 'isu' not in cols or 'repo' not in cols:
                raise RosterError('roster %s: the header must have the columns isu,repo (got %s)'
                                  % (path, ','.join(cols) or 'nothing'))
            rows = []
            for row in rd:
                row = {(k or '').strip(): (v or '').strip() if isinstance(v, str) else '' for k, v in row.items()}
                if not any(row.values()):
                    continue
                rows.append((rd.line_num, row))
    except OSError as e:
        raise RosterError('roster %s: %s' % (path, e.strerror))
    return rows, [c for c in cols if c not in ('isu', 'repo')]


def split_ref(spec):
    """'path-or-url[@ref]' -> (source, ref or None)."""
    if '@' in spec:
        left, right = spec.rsplit('@', 1)
        if left and right and ':' not in right:
            return left, right
    return spec, None


def _git(args, cwd=None, timeout=FETCH_TIMEOUT):
    env = dict(os.environ, GIT_TERMINAL_PROMPT='0', GIT_ASKPASS='true')
    r = subprocess.run(['git'] + args, cwd=cwd, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=timeout)
    text = r.stdout.decode(errors='replace').strip()
    return r.returncode, text


def last_line(text):
    lines = [l for l in text.splitlines() if l.strip()]
    return (lines[-1] if lines else 'no output')[:200]


def dir_digest(root):
    h = hashlib.sha1()
    for d, dirs, files in os.walk(root):
        dirs[:] = sorted(x for x in dirs if x not in ('.git', '__pycache__'))
        for f in sorted(files):
            p = os.path.join(d, f)
            h.update(os.path.relpath(p, root).encode())
            try:
                if os.path.islink(p):
                    h.update(os.readlink(p).encode())
                else:
                    with open(p, 'rb') as fh:
                        h.update(fh.read())
            except OSError:
                pass
    return 'dir:' + h.hexdigest()[:12]


def fetch(spec, dest, deadline=None):
    """Fetch the repository `spec` into dest; returns the commit id. RosterError on failure."""
    src, ref = split_ref(spec)
    if os.path.exists(dest):
        shutil.rmtree(dest)
    local = not re.match(r'^[a-z+]+://|^[^/]+@[^/]+:', src)
    if local:
        src = os.path.abspath(src)
        if not os.path.isdir(src):
            raise RosterError('repository %s does not exist' % src)
        if not os.path.isdir(os.path.join(src, '.git')):
            if ref or deadline:
                raise RosterError('%s is not a git repository (a ref or --deadline needs one)' % src)
            shutil.copytree(src, dest, symlinks=True)
            return dir_digest(dest)
    try:
        rc, out = _git(['clone', '--quiet', '--no-hardlinks' if local else '--no-local', src, dest])
        if rc != 0:
            raise RosterError('repository %s does not clone: %s' % (src, last_line(out)))
        target = ref or 'HEAD'
        if deadline:
            rc, out = _git(['rev-list', '-1', '--before=%s' % deadline, target], cwd=dest)
            if rc != 0 or not out.strip():
                raise RosterError('no commit of %s at %s before the deadline %s' % (src, target, deadline))
            target = out.split()[0]
        rc, out = _git(['checkout', '--quiet', '--detach', target], cwd=dest)
        if rc != 0:
            raise RosterError('ref %s of %s: %s' % (target, src, last_line(out)))
        rc, out = _git(['rev-parse', 'HEAD'], cwd=dest)
        return out.strip()[:40]
    except subprocess.TimeoutExpired:
        raise RosterError('repository %s: the clone did not finish within %d s' % (src, FETCH_TIMEOUT))


class ClassGrader:
    def __init__(self, lab, out, deadline=None, force=False, no_sandbox=False, timeout=None, log=sys.stderr,
                 variants=None):
        self.lab = lab
        self.variants = os.path.abspath(variants) if variants else None   # labs/grade --variants
        self.out = os.path.abspath(out)
        self.deadline = deadline
        self.force = force
        self.no_sandbox = no_sandbox
        self.timeout = timeout or LABS[lab].DEFAULT_TIMEOUT
        self.log = log
        self.lock = threading.Lock()
        self.done = self.running = 0
        self.total = 0
        self.durations = []
        self.t0 = time.monotonic()

    # --- rows ---
    def check_rows(self, rows):
        """[(line, row, error or None)] with bad ISUs and duplicates marked."""
        seen, out = {}, []
        for line, row in rows:
            isu, err = row.get('isu', ''), None
            if not isu.isdigit():
                err = 'ISU must be digits only, got %r' % isu
            elif isu in seen:
                err = 'duplicate ISU %s (also on roster line %d)' % (isu, seen[isu])
            elif not row.get('repo'):
                err = 'no repository given'
            if isu.isdigit() and isu not in seen:
                seen[isu] = line
            out.append((line, row, err))
        return out

    def row_dir(self, isu):
        return os.path.join(self.out, isu)

    def grade_row(self, row):
        """Fetch and grade one valid row; writes DIR/<isu>/result.json; returns the result."""
        isu, spec = row['isu'], row['repo']
        d = self.row_dir(isu)
        os.makedirs(d, exist_ok=True)
        res_path = os.path.join(d, RESULT)
        old = None
        if os.path.exists(res_path):
            try:
                with open(res_path) as f:
                    old = json.load(f)
            except (OSError, ValueError):
                old = None
        src = os.path.join(d, 'src')
        t = time.monotonic()
        try:
            commit = fetch(spec, src, self.deadline)
        except RosterError as e:
            return self._save(d, {'isu': isu, 'repo': spec, 'commit': '', 'status': 'error', 'error': str(e),
                                  'criteria': None, 'seconds': time.monotonic() - t})
        if (old and not self.force and old.get('commit') == commit and old.get('status') in ('passed', 'failed')
                and old.get('lab') == self.lab and old.get('variants') == self.variants):
            shutil.rmtree(src, ignore_errors=True)
            old['reused'] = True
            return old
        cmd = [GRADE, self.lab, '--isu', isu, '--repo', src, '--junit', os.path.join(d, 'junit.xml'),
               '--json', os.path.join(d, 'grade.json'), '--timeout', str(self.timeout),
               '--logs', os.path.join(d, 'logs'), '--hide', self.out]
        cmd.append('--no-sandbox' if self.no_sandbox else '--require-sandbox')
        if self.variants:
            cmd += ['--variants', self.variants]
        limit = self.timeout + BUILD_AND_SLACK
        for f in ('grade.json',):
            if os.path.exists(os.path.join(d, f)):
                os.remove(os.path.join(d, f))
        rc, timed_out = course_runtime.run(cmd, limit, log=os.path.join(d, 'grade.log'))
        shutil.rmtree(src, ignore_errors=True)
        res = {'isu': isu, 'repo': spec, 'commit': commit, 'lab': self.lab, 'seconds': time.monotonic() - t,
               'variants': self.variants}
        gj = os.path.join(d, 'grade.json')
        if timed_out:
            res.update(status='error', error='the grading hung: stopped after %d s' % limit, criteria=None)
        elif not os.path.exists(gj):
            with open(os.path.join(d, 'grade.log'), errors='replace') as f:
                res.update(status='error', criteria=None,
                           error='labs/grade failed (exit %s): %s' % (rc, last_line(f.read())))
        else:
            with open(gj) as f:
                g = json.load(f)
            crits = g['criteria']
            res.update(criteria=crits, note=g.get('note'),
                       status='passed' if crits and all(c['passed'] for c in crits) else 'failed')
        return self._save(d, res)

    def _save(self, d, res):
        res.setdefault('lab', self.lab)
        crits = [Criterion.from_dict(c) for c in res['criteria']] if res.get('criteria') else None
        with open(os.path.join(d, 'report.txt'), 'w') as f:
            if crits:
                f.write(format_report(self.lab, res['isu'], crits, note=res.get('note')) + '\n')
            else:
                f.write('%s, ISU %s: not graded: %s\n' % (self.lab, res['isu'], res.get('error')))
        if not crits:
            c = [Criterion(cid, ru, en, False, reason('не проверено: ' + res['error'], 'not graded: ' + res['error']))
                 for cid, ru, en in criteria_of(self.lab)]
            write_junit(os.path.join(d, 'junit.xml'), self.lab, res['isu'], c, res.get('seconds', 0.0))
        tmp = os.path.join(d, RESULT + '.tmp')
        with open(tmp, 'w') as f:
            json.dump(res, f, ensure_ascii=False, indent=1)
        os.replace(tmp, os.path.join(d, RESULT))
        return res

    # --- progress ---
    def progress(self, started=0, finished=None):
        with self.lock:
            self.running += started
            if finished is not None:
                self.running -= 1
                self.done += 1
                if not finished.get('reused'):
                    self.durations.append(finished.get('seconds', 0.0))
            left = self.total - self.done - self.running
            per = sum(self.durations) / len(self.durations) if self.durations else None
            jobs = max(1, self.jobs)
            eta = per * (left + self.running) / jobs if per is not None else None
            print('[grade-class] done %d/%d, running %d, left %d%s%s' % (
                self.done, self.total, self.running, left,
                ', %.0f s/row' % per if per is not None else '',
                ', ~%.0f s left' % eta if eta is not None else ''), file=self.log, flush=True)

    def run_local(self, rows, jobs):
        """Grade the valid rows [(line, row)] `jobs` at a time."""
        self.jobs = jobs

        def one(row):
            self.progress(started=1)
            try:
                res = self.grade_row(row)
            except Exception as e:   # a grader bug must not lose the rest of the class
                res = self._save(self.row_dir(row['isu']), {'isu': row['isu'], 'repo': row['repo'], 'commit': '',
                                                            'status': 'error', 'error': 'grader error: %s' % e,
                                                            'criteria': None})
            self.progress(finished=res)
            return res
        with ThreadPoolExecutor(max(1, jobs)) as ex:
            list(ex.map(one, [r for _l, r in rows]))

    # --- gradebook ---
    def gradebook(self, checked, extra):
        crit_defs = criteria_of(self.lab)
        cols = (['isu', 'repo', 'commit', 'status', 'score'] + ['c%s' % cid for cid, _ru, _en in crit_defs] + extra
                + ['note'])
        table = []
        for line, row, err in checked:
            r = {'isu': row.get('isu', ''), 'repo': row.get('repo', ''), 'commit': '', 'status': 'error', 'score': ''}
            for k in extra:
                r[k] = row.get(k, '')
            res = None
            if err is None:
                try:
                    with open(os.path.join(self.row_dir(row['isu']), RESULT)) as f:
                        res = json.load(f)
                except (OSError, ValueError):
                    err = 'not graded (the run was interrupted?)'
            if res is not None and res.get('criteria'):
                crits = res['criteria']
                n = sum(1 for c in crits if c['passed'])
                r.update(commit=res.get('commit', ''), status=res['status'], score='%d/%d' % (n, len(crits)),
                         note=res.get('note') or '')
                for c in crits:
                    r['c%s' % c['id']] = '%s: %s' % ('pass' if c['passed'] else 'FAIL', c['reason'].get('en', ''))
                    r['_ru_c%s' % c['id']] = c['reason'].get('ru', '')
            else:
                why = err or res.get('error', 'not graded')
                r.update(commit=(res or {}).get('commit', ''), note='line %d: %s' % (line, why))
                r['c0'] = 'ERROR: %s' % why
            table.append(r)
        with open(os.path.join(self.out, 'gradebook.csv'), 'w', newline='') as f:
            w = csv.DictWriter(f, fieldnames=cols, extrasaction='ignore')
            w.writeheader()
            w.writerows(table)
        self.write_html(table, cols, crit_defs)
        return table

    def write_html(self, table, cols, crit_defs):
        titles = {'c%s' % cid: '%s. %s<br><small>%s</small>' % (cid, html.escape(en), html.escape(ru))
                  for cid, ru, en in crit_defs}
        colour = {'passed': '#d7f5d7', 'failed': '#f9dcdc', 'error': '#f5e6b8'}
        out = ['<!DOCTYPE html><html><head><meta charset="utf-8"><title>%s gradebook</title>' % self.lab,
               '<style>body{font-family:sans-serif}table{border-collapse:collapse}td,th{border:1px solid #999;'
               'padding:3px;vertical-align:top;font-size:12px}.FAIL{color:#a00}.pass{color:#070}</style></head><body>',
               '<h1>%s: ведомость / gradebook</h1>' % self.lab,
               '<p>%d rows: %s</p>' % (len(table), ', '.join('%s %d' % (s, sum(1 for r in table if r['status'] == s))
                                                             for s in ('passed', 'failed', 'error'))),
               '<table><tr>%s</tr>' % ''.join('<th>%s</th>' % titles.get(c, html.escape(c)) for c in cols)]
        for r in table:
            cells = []
            for c in cols:
                v = r.get(c, '')
                if c in titles and v:
                    kind = v.split(':', 1)[0]
                    ru = r.get('_ru_' + c, '')
                    cells.append('<td class="%s">%s%s</td>' % (kind, html.escape(v),
                                                               '<br><small>%s</small>' % html.escape(ru)
                                                               if ru and kind == 'FAIL' else ''))
                else:
                    cells.append('<td>%s</td>' % html.escape(v))
            out.append('<tr style="background:%s">%s</tr>' % (colour.get(r['status'], '#fff'), ''.join(cells)))
        out.append('</table></body></html>')
        with open(os.path.join(self.out, 'gradebook.html'), 'w') as f:
            f.write('\n'.join(out) + '\n')


def parser():
    ap = argparse.ArgumentParser(prog='labs/grade-class', description=__doc__.splitlines()[0])
    ap.add_argument('lab', help='lab1, lab2, lab3 or lab4')
    ap.add_argument('--roster', required=True, help='CSV with the columns isu,repo (repo: a path or git URL[@ref])')
    ap.add_argument('--jobs', type=int, default=max(1, (os.cpu_count() or 2) // 2),
                    help='rows at a time (default: cores / 2)')
    ap.add_argument('--out', help='output folder (default: grade-class-LAB)')
    ap.add_argument('--backend', choices=('local', 'slurm'), default='local')
    ap.add_argument('--deadline', help='grade the last commit before this date (git --before syntax)')
    ap.add_argument('--force', action='store_true', help='re-grade every row, even at an unchanged commit')
    ap.add_argument('--no-sandbox', action='store_true', help='grade without the sandbox (trusted code only)')
    ap.add_argument('--timeout', type=float, help="the checker's time limit per row, s (default: the lab's)")
    ap.add_argument('--variants', metavar='FILE', help="grade by this variant table instead of the textbook's "
                    '(labs/grade --variants)')
    ap.add_argument('--task', type=int, help=argparse.SUPPRESS)   # one roster row (a Slurm array task)
    return ap


def checked_roster(args):
    """(roster rows, extra column names); RosterError on a bad command line, roster or table,
    or when no sandbox can be made and --no-sandbox was not given."""
    if args.lab not in LABS:
        raise RosterError('unknown lab %r: expected one of %s' % (args.lab, ', '.join(sorted(LABS))))
    if args.jobs < 1:
        raise RosterError('--jobs must be at least 1, got %d' % args.jobs)
    rows, extra = read_roster(args.roster)
    if args.variants:
        try:
            load_variants(args.lab, os.path.abspath(args.variants))
        except GradeError as e:
            raise RosterError(str(e))
    if not args.no_sandbox:
        why = sandbox.probe()
        if why:
            raise RosterError('no grading sandbox can be made here (%s); give --no-sandbox to grade '
                              'unsandboxed (trusted code only)' % why)
    return rows, extra


def grade_rows(g, args, valid, checked, out):
    """Grade the valid rows locally or on Slurm (or the one row of a Slurm array task)."""
    if args.task is not None:           # one Slurm array task: grade one valid row
        g.jobs = 1
        g.grade_row(valid[args.task][1])
        return
    g.total = len(valid)
    print('[grade-class] %s: %d roster rows, %d to grade, backend %s, %d at a time -> %s'
          % (args.lab, len(checked), len(valid), args.backend, args.jobs, os.path.abspath(out)),
          file=sys.stderr, flush=True)
    if args.backend == 'slurm':
        slurm.run_array(g, args, valid)
    else:
        g.run_local(valid, args.jobs)


def main(argv=None):
    args = parser().parse_args(argv)
    try:
        rows, extra = checked_roster(args)
    except RosterError as e:
        print('labs/grade-class: error: %s' % e, file=sys.stderr)
        return 2
    out = args.out or 'grade-class-%s' % args.lab
    os.makedirs(out, exist_ok=True)
    g = ClassGrader(args.lab, out, args.deadline, args.force, args.no_sandbox, args.timeout, variants=args.variants)
    checked = g.check_rows(rows)
    valid = [(l, r) for l, r, e in checked if e is None]
    course_runtime.become_subreaper()
    try:
        grade_rows(g, args, valid, checked, out)
        if args.task is not None:
            return 0
    except KeyboardInterrupt:
        print('labs/grade-class: interrupted; rows done are kept, run again to resume', file=sys.stderr)
        g.gradebook(checked, extra)
        return 130
    finally:
        course_runtime.reap_orphans()
    table = g.gradebook(checked, extra)
    counts = {s: sum(1 for r in table if r['status'] == s) for s in ('passed', 'failed', 'error')}
    print('[grade-class] gradebook: %s (passed %d, failed %d, error %d)'
          % (os.path.join(os.path.abspath(out), 'gradebook.csv'), counts['passed'], counts['failed'], counts['error']))
    return 0
