"""labs/grade LAB --isu ID [--repo PATH] [--junit FILE] [--timeout S] [--variants FILE] [--no-sandbox]

Finds the lab's package in the student's repository, builds it in a fresh overlay workspace
on top of the course workspace, runs the lab's rostest for the variant (last ISU digit),
prints a per-criterion report (ru/en) and, with --junit, writes JUnit XML. Exit 0 only if all
criteria pass. The variant table is the textbook's (labs/LAB/variants.yaml) unless --variants
names a corrected one (same format, validated first).
"""
import argparse
import json
import os
import re
import shutil
import sys
import tempfile
import time

import course_runtime
import yaml

from grading import sandbox
from grading.common import LABS_DIR, VARIANTS_ENV, Criterion, GradeError, parse_isu, read_report, reason
from grading.labs import LABS, load_variants
from grading.report import format_report, write_junit
from grading.workspace import StepFailed, build_overlay, course_env, locate, run_group

BUILD_TIMEOUT = 300.0


def package_criterion():
    return Criterion('0', 'Пакет найден и собирается', 'Package found and builds')


def lab_criteria(mod, why=None):
    return [Criterion(cid, ru, en, False, why) for cid, ru, en in mod.CRITERIA]


def tail(path, n=5):
    try:
        with open(path, errors='replace') as f:
            lines = [l.strip() for l in f.read().splitlines() if l.strip()]
        return ' | '.join(lines[-n:])[-400:]
    except OSError:
        return 'no log'


def checker_crash(work):
    """The exception line of a checker that failed with a Python traceback, or None."""
    for d, _dirs, files in os.walk(os.path.join(work, 'ros_log')):
        for f in files:
            if f.endswith('-stdout.log'):
                with open(os.path.join(d, f), errors='replace') as fh:
                    text = fh.read()
                if 'Traceback (most recent call last)' in text:
                    errs = [l.strip() for l in text.splitlines()
                            if re.match(r'^[A-Za-z_.]*(Error|Exception)\b.*:', l.strip())]
                    return (errs[-1] if errs else 'a Python exception (see the rostest log)')[:250]
    return None


def write_variants(lab, path, work):
    """The validated table of `path` as work/variants.yaml, where the checker reads it."""
    table = load_variants(lab, path)
    out = os.path.join(work, 'variants.yaml')
    with open(out, 'w') as f:
        yaml.safe_dump({'source': os.path.abspath(path), 'variants': table}, f, allow_unicode=True)
    return out


def run_checker(lab, isu, env, work, timeout, box=None, variants=None):
    """Run the lab's rostest; return the checker's criteria (or None) and a log path.
    With a sandbox `box` the rostest (master and checker) runs in a network namespace of its
    own, and the checker starts the student's nodes inside the sandbox. `variants`: a variant
    table file to use instead of the textbook's."""
    mod = LABS[lab]
    report = os.path.join(work, 'report.json')
    env = dict(env)
    env['GRADING_REPORT'] = report
    env.pop(VARIANTS_ENV, None)
    if variants:
        env[VARIANTS_ENV] = write_variants(lab, variants, work)
    if box is not None:
        env['GRADING_SANDBOX'] = box.to_json()
        env.pop('DISPLAY', None)   # the grading's network namespace cannot reach the user's X server
    env['ROS_PACKAGE_PATH'] = env.get('ROS_PACKAGE_PATH', '') + ':' + os.path.join(LABS_DIR, lab, 'grader')
    env['PYTHONPATH'] = LABS_DIR + ':' + env.get('PYTHONPATH', '')
    env['ROS_LOG_DIR'] = os.path.join(work, 'ros_log')
    env['ROS_HOME'] = os.path.join(work, 'ros_home')
    env.setdefault('ROS_IP', '127.0.0.1')
    env.pop('ROS_HOSTNAME', None)
    if not env.get('DISPLAY'):
        env['QT_QPA_PLATFORM'] = 'offscreen'
    log = os.path.join(work, 'rostest.log')
    cmd = ['rostest', '--results-base-dir', os.path.join(work, 'results'),
           mod.GRADER_PKG, lab + '.test', 'isu:=' + isu, 'workdir:=' + work]
    if box is not None:
        cmd = sandbox.netns_prefix() + cmd
    rc, timed_out = run_group(cmd, timeout, env=env, cwd=work, log=log)
    crits = read_report(report) if os.path.exists(report) else None
    return crits, log, timed_out


def save_logs(work, dest):
    """Copy the grading's logs (build, rostest, the student's launch) into dest."""
    os.makedirs(dest, exist_ok=True)
    for d, _dirs, files in os.walk(work):
        if (d + '/').startswith(os.path.join(work, 'ws') + '/'):
            continue
        for f in files:
            if f.endswith('.log') or f.endswith('.xml'):
                try:
                    shutil.copy(os.path.join(d, f), os.path.join(dest, f))
                except OSError:
                    pass


def grade(lab, isu, repo, timeout, keep=False, out=sys.stdout, sandboxed=True, hide=(), logs=None,
          variants=None):
    """Returns the list of criteria (package criterion first). `sandboxed`: the student's
    build and nodes run in the grading sandbox (grading.sandbox); `hide`: more folders of the
    course tree the sandbox must not see (other submissions); `variants`: a variant table file
    instead of the textbook's."""
    mod = LABS[lab]
    pkg_c = package_criterion()
    work = tempfile.mkdtemp(prefix='grade-%s-%s-' % (lab, isu))
    ws = os.path.join(work, 'ws')
    box = None
    if sandboxed:
        box = sandbox.Sandbox(sandbox.new_uid(), ws, hide=[repo] + list(hide))
        box.prepare_ws(ws)
    try:
        env = course_env()
        try:
            pkg_dir = locate(repo, mod.PACKAGE)
            print('[grade] found %s in %s; building it in %s%s' % (mod.PACKAGE, pkg_dir, work,
                  ' (sandboxed)' if box else ''), file=out, flush=True)
            t = time.monotonic()
            run_env = build_overlay(pkg_dir, ws, env, BUILD_TIMEOUT, box=box,
                                    log=os.path.join(work, 'build.log'))
            if box is not None:
                # the checker keeps the course's environment; only the overlay's package path
                box.student_env = run_env
                run_env = dict(env, ROS_PACKAGE_PATH=os.path.join(ws, 'src') + ':' + env.get('ROS_PACKAGE_PATH', ''))
            pkg_c.set(True, reason('пакет %s собран за %.0f с' % (mod.PACKAGE, time.monotonic() - t),
                                   'package %s built in %.0f s' % (mod.PACKAGE, time.monotonic() - t)))
        except StepFailed as e:
            pkg_c.set(False, e.reason)
            return [pkg_c] + lab_criteria(mod, reason('не проверено: ' + e.reason['ru'],
                                                      'not checked: ' + e.reason['en']))
        print('[grade] running the %s checker (rostest, time limit %d s)' % (lab, timeout), file=out, flush=True)
        crits, log, timed_out = run_checker(lab, isu, run_env, work, timeout, box=box, variants=variants)
        if crits is None:
            crash = checker_crash(work)
            if timed_out:
                why, why_ru = ('the checker hit the %d s time limit' % timeout,
                               'проверка не уложилась в %d с' % timeout)
            elif crash:
                why, why_ru = 'the checker failed: %s' % crash, 'ошибка проверяющей программы: %s' % crash
            else:
                why = 'tampering: the checker ended without writing its report (killed?)'
                why_ru = 'tampering: проверка завершилась, не записав отчёт (её убили?)'
            last = tail(log)
            return [pkg_c] + lab_criteria(mod, reason('%s (%s)' % (why_ru, last), '%s (%s)' % (why, last)))
        return [pkg_c] + crits
    finally:
        if logs:
            save_logs(work, logs)
        sandbox.release_ws(ws)
        if keep:
            print('[grade] work dir kept: %s' % work, file=out)
        else:
            shutil.rmtree(work, ignore_errors=True)


def parser():
    ap = argparse.ArgumentParser(prog='labs/grade', description=__doc__.splitlines()[0])
    ap.add_argument('lab', help='lab1, lab2, lab3 or lab4')
    ap.add_argument('--isu', required=True, help='your ISU id (digits); its last digit is the variant')
    ap.add_argument('--repo', default='.', help='folder with your lab repository (default: .)')
    ap.add_argument('--junit', help='also write the criteria as JUnit XML to this file')
    ap.add_argument('--variants', metavar='FILE',
                    help='variant table to grade by instead of the textbook\'s labs/LAB/variants.yaml '
                         '(same format; for an instructor\'s corrected table)')
    ap.add_argument('--timeout', type=float, help='time limit of the checker run, s')
    ap.add_argument('--keep', action='store_true', help='keep the temporary work dir (logs)')
    ap.add_argument('--no-sandbox', action='store_true',
                    help='build and run your nodes without the grading sandbox (debugging)')
    ap.add_argument('--json', help='also write the criteria as JSON to this file (labs/grade-class)')
    ap.add_argument('--hide', action='append', default=[], help=argparse.SUPPRESS)
    ap.add_argument('--logs', help=argparse.SUPPRESS)
    ap.add_argument('--require-sandbox', action='store_true', help=argparse.SUPPRESS)
    return ap


def sandbox_choice(args):
    """(sandboxed, self-check note or None) for the command line: a sandbox unless
    --no-sandbox or none can be made here (then a self-check, unless --require-sandbox)."""
    sandboxed, note = not args.no_sandbox, None
    if sandboxed:
        why = sandbox.probe()
        if why:
            if args.require_sandbox:
                raise GradeError('no grading sandbox can be made here (%s)' % why)
            print('labs/grade: no sandbox can be made here (%s): grading without one, as a self-check' % why,
                  file=sys.stderr, flush=True)
            sandboxed, note = False, 'self-check: graded without a sandbox (%s)' % why
    if args.no_sandbox:
        note = 'self-check: graded with --no-sandbox'
    return sandboxed, note


def checked_args(args):
    """(isu, repo, timeout, variants file or None) of the command line; GradeError on bad input."""
    if args.lab not in LABS:
        raise GradeError('unknown lab %r: expected one of %s' % (args.lab, ', '.join(sorted(LABS))))
    isu = parse_isu(args.isu)
    repo = os.path.abspath(args.repo)
    timeout = args.timeout or LABS[args.lab].DEFAULT_TIMEOUT
    if timeout <= 0:
        raise GradeError('--timeout must be positive, got %s' % args.timeout)
    variants = None
    if args.variants:
        variants = os.path.abspath(args.variants)
        load_variants(args.lab, variants)   # a bad table stops here, before any build
    return isu, repo, timeout, variants


def write_outputs(args, isu, crits, elapsed, note, sandboxed, variants):
    """The console report, and the JUnit and JSON files where asked."""
    print(format_report(args.lab, isu, crits, note=note))
    if args.junit:
        os.makedirs(os.path.dirname(os.path.abspath(args.junit)), exist_ok=True)
        write_junit(args.junit, args.lab, isu, crits, elapsed, note=note, variants=variants)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump({'lab': args.lab, 'isu': isu, 'sandboxed': sandboxed, 'note': note,
                       'criteria': [c.to_dict() for c in crits]}, f, ensure_ascii=False, indent=1)
    if args.junit:
        print('[grade] JUnit report: %s' % os.path.abspath(args.junit))


def main(argv=None):
    args = parser().parse_args(argv)
    course_runtime.become_subreaper()   # nodes orphaned by a crashed launch come back to us
    try:
        isu, repo, timeout, variants = checked_args(args)
        sandboxed, note = sandbox_choice(args)
        t0 = time.monotonic()
        if variants:
            print('[grade] variant table: %s (--variants), not the textbook\'s' % variants, flush=True)
        crits = grade(args.lab, isu, repo, timeout, keep=args.keep, sandboxed=sandboxed,
                      hide=[os.path.abspath(h) for h in args.hide], logs=args.logs, variants=variants)
    except GradeError as e:
        print('labs/grade: error: %s' % e, file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print('labs/grade: interrupted', file=sys.stderr)
        return 130
    finally:
        course_runtime.reap_orphans()   # nothing of the student's run outlives the grader
    write_outputs(args, isu, crits, time.monotonic() - t0, note, sandboxed, variants)
    return 0 if all(c.passed for c in crits) else 1
