#!/usr/bin/env python3
"""Run every pytest test, gtest executable and rostest of the repository; print one closing line.

The closing line is `N passed, N failed, N skipped`, aggregated from the JUnit XML files the
runs write (pytest's --junitxml and rostest's results). Exit status is non-zero when anything
failed, when a run produced no result file, or when a run hit its time limit.

Order: the tests marked `serial` (they rebuild the shared workspace) run alone first; then
pytest on `--jobs` workers (pytest-xdist, whole files per worker) runs beside a second lane of
every gtest and rostest. Every test has a master, ports and an X display of its own, so they
do not meet; the machine is busier than with one test at a time, which the tests are built
to stand (scripts/stress.sh checks that with every core saturated).
"""
import argparse
import glob
import json
import os
import sys
import threading
import time
import xml.etree.ElementTree as ET

import course_testing   # catkin_ws/src/tools/course_testing (scripts/test.sh sources the workspace)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(REPO, 'build', 'test-results')
ROSTEST_TIMEOUT = 900


class Runner:
    """Runs test commands, possibly from two lanes at once. After each command it kills and
    names what that command left behind (a test must clean up its roscore, nodes and Xvfb),
    leaving alone the process trees of commands still running in the other lane."""

    def __init__(self):
        self.lock = threading.Lock()
        self.active = set()

    def _started(self, popen):
        self.active.add(popen.pid)

    def run(self, cmd, timeout, env=None, log=None, say=print):
        holder = {}

        def started(popen):
            holder['pid'] = popen.pid
            self._started(popen)
        rc, timed_out = course_testing.run(cmd, timeout, env=env, cwd=REPO, log=log,
                                           started=started, lock=self.lock)
        with self.lock:
            self.active.discard(holder.get('pid'))
            leaked = course_testing.reap_orphans(keep=tuple(self.active))
        if leaked:
            say('WARNING: %s left %d processes running (killed now): %s' % (
                ' '.join(cmd[:3]), len(leaked), '; '.join(leaked[:5])))
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


class Lane:
    """One sequence of test commands; its messages are kept and printed in one block when
    the lane runs beside the pytest lane (so the two outputs do not interleave)."""

    def __init__(self, buffered):
        self.buffered = buffered
        self.lines = []
        self.problems = []   # runs that produced no usable results
        self.xmls = []
        self.durations = []  # (seconds, name)

    def say(self, text):
        if self.buffered:
            self.lines.append(text)
        else:
            print(text, flush=True)

    def flush(self):
        for text in self.lines:
            print(text, flush=True)
        self.lines = []


def pytest_lane(runner, lane, env, args, marker, workers, junit):
    cmd = [sys.executable, '-m', 'pytest', '-rfEs', '--junitxml', junit, '-m', marker]
    if workers > 1:
        # whole files per worker: module fixtures (one launch shared by its tests) stay together
        cmd += ['-n', str(workers), '--dist', 'loadfile']
    if args.keyword:
        cmd += ['-k', args.keyword]
    lane.say('=== pytest -m "%s"%s' % (marker, ' on %d workers' % workers if workers > 1 else ''))
    rc, timed_out = runner.run(cmd, 3600, env=env, say=lane.say)
    if timed_out:
        lane.problems.append('pytest -m "%s": hit the 3600 s time limit' % marker)
    if os.path.exists(junit):
        lane.xmls.append(junit)
        lane.durations += pytest_durations(junit)
    elif rc not in (0, 5):  # 5 = nothing collected
        lane.problems.append('pytest -m "%s": exited %s without a result file' % (marker, rc))


def gtest_lane(runner, lane, env, args):
    for exe in gtest_executables():
        name = os.path.basename(exe)
        if args.keyword and args.keyword not in name:
            continue
        xml = os.path.join(RESULTS, 'gtest', name + '.xml')
        log = os.path.join(RESULTS, 'gtest', name + '.log')
        os.makedirs(os.path.dirname(xml), exist_ok=True)
        lane.say('=== gtest %s' % os.path.relpath(exe, REPO))
        t = time.monotonic()
        rc, timed_out = runner.run([exe, '--gtest_output=xml:' + xml], 600, env=env, log=log,
                                   say=lane.say)
        lane.durations.append((time.monotonic() - t, 'gtest ' + name))
        if timed_out:
            lane.problems.append('%s: hit the 600 s time limit' % name)
        if os.path.exists(xml):
            lane.xmls.append(xml)
        else:
            lane.problems.append('%s: exited %s without a result file (see %s)' % (
                name, rc, os.path.relpath(log, REPO)))
        if rc != 0:
            with open(log) as fh:
                lane.say(''.join(fh.readlines()[-30:]))


def rostest_lane(runner, lane, env, args):
    for f in rostest_files():
        if args.keyword and args.keyword not in os.path.basename(f):
            continue
        pkg = package_of(f)
        rel = os.path.relpath(f, REPO)
        outdir = os.path.join(RESULTS, 'rostest', pkg + '-' + os.path.basename(f)[:-5])
        log = outdir + '.log'
        os.makedirs(outdir, exist_ok=True)
        t = time.monotonic()
        rc, timed_out = runner.run(['rostest', '--results-base-dir', outdir, f], ROSTEST_TIMEOUT,
                                   env=env, log=log, say=lane.say)
        found = [x for x in glob.glob(os.path.join(outdir, '**', '*.xml'), recursive=True)
                 if not os.path.basename(x).startswith('rostest-')]
        summary = [x for x in glob.glob(os.path.join(outdir, '**', 'rostest-*.xml'), recursive=True)]
        p, fl = 0, 0
        for x in found or summary:
            a, b, _c, _n = count_junit(x)
            p, fl = p + a, fl + b
        status = 'ok' if rc == 0 and not fl else 'FAILED'
        lane.durations.append((time.monotonic() - t, 'rostest ' + rel))
        lane.say('=== rostest %s %s\n    %s: %d passed, %d failed (%.0f s, log %s)' % (
            pkg, rel, status, p, fl, time.monotonic() - t, os.path.relpath(log, REPO)))
        if timed_out:
            lane.problems.append('%s: hit the %d s time limit' % (rel, ROSTEST_TIMEOUT))
        elif rc != 0 and not fl:
            lane.problems.append('%s: rostest exited %d (see %s)' % (rel, rc, os.path.relpath(log, REPO)))
        if rc != 0 or fl:
            with open(log) as fh:
                lane.say(''.join(fh.readlines()[-30:]))
        lane.xmls.extend(found or summary)


def default_jobs():
    return int(os.environ.get('COURSE_TEST_JOBS') or 2)


def arguments():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--full', action='store_true', help='also run tests marked `full`')
    ap.add_argument('-k', dest='keyword', help='pytest -k expression; rostests: substring of file name')
    ap.add_argument('-j', '--jobs', type=int, default=default_jobs(),
                    help='pytest workers (pytest-xdist); with more than one, the gtests and rostests '
                         'run beside them in a lane of their own (default: $COURSE_TEST_JOBS or 2; '
                         '1 = everything one after the other)')
    ap.add_argument('--no-rostest', action='store_true')
    ap.add_argument('--no-pytest', action='store_true')
    ap.add_argument('--no-gtest', action='store_true')
    return ap.parse_args()


def test_env(args):
    """The environment of every test command."""
    env = dict(os.environ)
    env['ROS_LOG_DIR'] = os.path.join(RESULTS, 'ros_log')
    # Python nodes print as on a terminal (line by line), whatever the caller's environment:
    # tests read nodes' output from files, where Python would otherwise keep up to 8 KiB
    # (a talker's first minute) in its buffer - a fresh Debian 13 container has no
    # PYTHONUNBUFFERED in its environment and 4 tests waited for output that never came
    env['PYTHONUNBUFFERED'] = '1'
    # OpenGL (RViz and Qt windows on the tests' Xvfb, the simulator's cameras through EGL) is
    # drawn by Mesa's softpipe: llvmpipe's JIT crashes now and then inside Debian 12's LLVM 15
    # (course_testing.SOFTWARE_GL); the GUI tests take as long
    env.update(course_testing.SOFTWARE_GL)
    env['COURSE_TEST_FULL'] = '1' if args.full else ''
    return env


def summarise(lanes, args, concurrent, t0):
    """Prints the slowest tests, the failures and the closing line; writes summary.json; the
    exit status."""
    problems = [p for lane in lanes for p in lane.problems]
    durations = [d for lane in lanes for d in lane.durations]
    passed = failed = skipped = 0
    failures = []
    for x in (x for lane in lanes for x in lane.xmls):
        a, b, c, names = count_junit(x)
        passed, failed, skipped = passed + a, failed + b, skipped + c
        failures += names
    failed += len(problems)
    print('\n=== ten slowest')
    for sec, name in sorted(durations, reverse=True)[:10]:
        print('%7.1f s  %s' % (sec, name))
    print('\n=== summary (%.0f s%s)' % (time.monotonic() - t0,
                                        ', %d pytest workers beside the rostests' % args.jobs
                                        if concurrent else ''))
    for name in failures:
        print('FAILED', name)
    for pr in problems:
        print('FAILED', pr)
    with open(os.path.join(RESULTS, 'summary.json'), 'w') as fh:   # read by scripts/stress.py
        json.dump({'passed': passed, 'failed': failed, 'skipped': skipped,
                   'failures': failures + problems, 'seconds': time.monotonic() - t0,
                   'jobs': args.jobs, 'durations': sorted(durations, reverse=True)}, fh, indent=1)
    line = '%d passed, %d failed' % (passed, failed)
    if skipped:
        line += ', %d skipped' % skipped
    print(line, flush=True)
    return 1 if failed or passed == 0 else 0


def main():
    args = arguments()
    course_testing.become_subreaper()   # orphans of a test come back to us and are killed
    os.makedirs(RESULTS, exist_ok=True)
    for old in glob.glob(os.path.join(RESULTS, '**', '*.xml'), recursive=True):
        os.remove(old)
    env = test_env(args)
    runner = Runner()
    t0 = time.monotonic()
    concurrent = args.jobs > 1
    not_full = '' if args.full else ' and not full'

    # 1. tests that change the shared workspace itself (setup.sh, catkin_make) run alone
    first = Lane(buffered=False)
    if not args.no_pytest:
        pytest_lane(runner, first, env, args, 'serial' + not_full, 1,
                    os.path.join(RESULTS, 'pytest-serial.xml'))

    # 2. pytest (on `jobs` workers) beside the gtests + rostests
    main_lane = Lane(buffered=False)
    ros_lane = Lane(buffered=concurrent)

    def ros_tests():
        if not args.no_gtest:
            gtest_lane(runner, ros_lane, env, args)
        if not args.no_rostest:
            rostest_lane(runner, ros_lane, env, args)

    side = threading.Thread(target=ros_tests, name='ros-lane')
    if concurrent:
        side.start()
    if not args.no_pytest:
        pytest_lane(runner, main_lane, env, args, 'not serial' + not_full, args.jobs,
                    os.path.join(RESULTS, 'pytest.xml'))
    if concurrent:
        side.join()
    else:
        ros_tests()
    ros_lane.flush()
    leaked = course_testing.reap_orphans()
    if leaked:
        print('WARNING: %d processes were still running at the end (killed now): %s' % (
            len(leaked), '; '.join(leaked[:5])), flush=True)

    return summarise((first, main_lane, ros_lane), args, concurrent, t0)


if __name__ == '__main__':
    sys.exit(main())
