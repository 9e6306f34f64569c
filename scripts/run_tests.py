#!/usr/bin/env python3
"""Run every pytest test, gtest executable and rostest of the repository; print one closing line.

The closing line is `N passed, N failed, N skipped`, aggregated from the JUnit XML files the
runs write (pytest's --junitxml and rostest's results). Exit status is non-zero when anything
failed, when a run produced no result file, or when a run hit its time limit.
"""
import argparse
import glob
import json
import os
import sys
import time
import xml.etree.ElementTree as ET

import course_testing   # catkin_ws/src/tools/course_testing (scripts/test.sh sources the workspace)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(REPO, 'build', 'test-results')
ROSTEST_TIMEOUT = 900


def run(cmd, timeout, env=None, log=None):
    """Run one test command with its whole process tree stopped on timeout; then kill and name
    whatever it left behind (a test must clean up its roscore, nodes and Xvfb)."""
    rc, timed_out = course_testing.run(cmd, timeout, env=env, cwd=REPO, log=log)
    leaked = course_testing.reap_orphans()
    if leaked:
        print('WARNING: %s left %d processes running (killed now): %s' % (
            ' '.join(cmd[:3]), len(leaked), '; '.join(leaked[:5])), flush=True)
    return (-1 if rc is None else rc), timed_out


def count_junit(path):
    """(passed, failed, skipped, failure names) of one JUnit XML file."""
    passed = failed = skipped = 0
    names = []
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        return 0, 1, 0, ['%s: unreadable result file (%s)' % (path, e)]
    for case in root.iter('testcase'):
        name = '%s.%s' % (case.get('classname', ''), case.get('name', ''))
        if name.startswith('__main__.'):   # rostest nodes: name the result file instead
            name = '%s: %s' % (os.path.basename(path)[:-4], name[len('__main__.'):])
        if case.find('failure') is not None or case.find('error') is not None:
            failed += 1
            names.append(name)
        elif case.find('skipped') is not None:
            skipped += 1
        else:
            passed += 1
    return passed, failed, skipped, names


def pytest_durations(path):
    """(seconds, name) of every test case in pytest's JUnit XML."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError):
        return []
    return [(float(c.get('time') or 0), '%s::%s' % (c.get('classname', ''), c.get('name', '')))
            for c in root.iter('testcase')]


def package_of(path):
    d = os.path.dirname(path)
    while d != REPO and d != '/':
        pxml = os.path.join(d, 'package.xml')
        if os.path.exists(pxml):
            return ET.parse(pxml).getroot().findtext('name').strip()
        d = os.path.dirname(d)
    return None


def rostest_files():
    files = glob.glob(os.path.join(REPO, 'catkin_ws', 'src', '**', 'test', '*.test'), recursive=True)
    return sorted(f for f in files if package_of(f))


def gtest_executables():
    """The C++ unit tests: catkin_add_gtest targets named gtest_*, built by scripts/setup.sh
    (`catkin_make all tests`) into catkin_ws/devel/lib/<package>/."""
    found = glob.glob(os.path.join(REPO, 'catkin_ws', 'devel', 'lib', '*', 'gtest_*'))
    return sorted(f for f in found if os.path.isfile(f) and os.access(f, os.X_OK))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--full', action='store_true', help='also run tests marked `full`')
    ap.add_argument('-k', dest='keyword', help='pytest -k expression; rostests: substring of file name')
    ap.add_argument('--no-rostest', action='store_true')
    ap.add_argument('--no-pytest', action='store_true')
    ap.add_argument('--no-gtest', action='store_true')
    args = ap.parse_args()

    course_testing.become_subreaper()   # orphans of a test come back to us and are killed
    os.makedirs(RESULTS, exist_ok=True)
    for old in glob.glob(os.path.join(RESULTS, '**', '*.xml'), recursive=True):
        os.remove(old)
    env = dict(os.environ)
    env['ROS_LOG_DIR'] = os.path.join(RESULTS, 'ros_log')
    env['COURSE_TEST_FULL'] = '1' if args.full else ''

    problems = []   # runs that produced no usable results
    xmls = []
    durations = []  # (seconds, name) of every test case and rostest file: the slowest are listed
    t0 = time.monotonic()

    if not args.no_pytest:
        junit = os.path.join(RESULTS, 'pytest.xml')
        cmd = [sys.executable, '-m', 'pytest', '-rfEs', '--junitxml', junit]
        if not args.full:
            cmd += ['-m', 'not full']
        if args.keyword:
            cmd += ['-k', args.keyword]
        print('=== pytest', flush=True)
        rc, timed_out = run(cmd, 3600, env=env)
        if timed_out:
            problems.append('pytest: hit the 3600 s time limit')
        if os.path.exists(junit):
            xmls.append(junit)
        elif rc not in (0, 5):  # 5 = nothing collected
            problems.append('pytest: exited %s without a result file' % rc)

    if not args.no_gtest:
        for exe in gtest_executables():
            name = os.path.basename(exe)
            if args.keyword and args.keyword not in name:
                continue
            xml = os.path.join(RESULTS, 'gtest', name + '.xml')
            log = os.path.join(RESULTS, 'gtest', name + '.log')
            os.makedirs(os.path.dirname(xml), exist_ok=True)
            print('=== gtest %s' % os.path.relpath(exe, REPO), flush=True)
            t = time.monotonic()
            rc, timed_out = run([exe, '--gtest_output=xml:' + xml], 600, env=env, log=log)
            durations.append((time.monotonic() - t, 'gtest ' + name))
            if timed_out:
                problems.append('%s: hit the 600 s time limit' % name)
            if os.path.exists(xml):
                xmls.append(xml)
            else:
                problems.append('%s: exited %s without a result file (see %s)' % (
                    name, rc, os.path.relpath(log, REPO)))
            if rc != 0:
                with open(log) as fh:
                    print(''.join(fh.readlines()[-30:]), flush=True)

    if not args.no_rostest:
        for f in rostest_files():
            if args.keyword and args.keyword not in os.path.basename(f):
                continue
            pkg = package_of(f)
            rel = os.path.relpath(f, REPO)
            outdir = os.path.join(RESULTS, 'rostest', pkg + '-' + os.path.basename(f)[:-5])
            log = outdir + '.log'
            os.makedirs(outdir, exist_ok=True)
            print('=== rostest %s %s' % (pkg, rel), flush=True)
            t = time.monotonic()
            rc, timed_out = run(['rostest', '--results-base-dir', outdir, f], ROSTEST_TIMEOUT,
                                env=env, log=log)
            found = [x for x in glob.glob(os.path.join(outdir, '**', '*.xml'), recursive=True)
                     if not os.path.basename(x).startswith('rostest-')]
            summary = [x for x in glob.glob(os.path.join(outdir, '**', 'rostest-*.xml'), recursive=True)]
            p, fl, s, _ = (0, 0, 0, [])
            for x in found or summary:
                a, b, c, _n = count_junit(x)
                p, fl, s = p + a, fl + b, s + c
            status = 'ok' if rc == 0 and not fl else 'FAILED'
            durations.append((time.monotonic() - t, 'rostest ' + rel))
            print('    %s: %d passed, %d failed (%.0f s, log %s)' % (
                status, p, fl, time.monotonic() - t, os.path.relpath(log, REPO)), flush=True)
            if timed_out:
                problems.append('%s: hit the %d s time limit' % (rel, ROSTEST_TIMEOUT))
            elif rc != 0 and not fl:
                problems.append('%s: rostest exited %d (see %s)' % (rel, rc, os.path.relpath(log, REPO)))
            if rc != 0 or fl:
                with open(log) as fh:
                    print(''.join(fh.readlines()[-30:]), flush=True)
            xmls.extend(found or summary)

    passed = failed = skipped = 0
    failures = []
    for x in xmls:
        a, b, c, names = count_junit(x)
        passed, failed, skipped = passed + a, failed + b, skipped + c
        failures += names
    failed += len(problems)
    if os.path.exists(os.path.join(RESULTS, 'pytest.xml')):
        durations += pytest_durations(os.path.join(RESULTS, 'pytest.xml'))
    print('\n=== ten slowest')
    for sec, name in sorted(durations, reverse=True)[:10]:
        print('%7.1f s  %s' % (sec, name))
    print('\n=== summary (%.0f s)' % (time.monotonic() - t0))
    for name in failures:
        print('FAILED', name)
    for pr in problems:
        print('FAILED', pr)
    with open(os.path.join(RESULTS, 'summary.json'), 'w') as fh:   # read by scripts/stress.py
        json.dump({'passed': passed, 'failed': failed, 'skipped': skipped,
                   'failures': failures + problems, 'seconds': time.monotonic() - t0,
                   'durations': sorted(durations, reverse=True)}, fh, indent=1)
    line = '%d passed, %d failed' % (passed, failed)
    if skipped:
        line += ', %d skipped' % skipped
    print(line, flush=True)
    return 1 if failed or passed == 0 else 0


if __name__ == '__main__':
    sys.exit(main())
