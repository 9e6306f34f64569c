#!/usr/bin/env python3
"""`make test-stress`: the whole test suite with every core kept busy, N rounds in a row.

Flaky tests show up here: each round runs scripts/run_tests.py (the gate, or --full) while
stress-ng keeps one CPU worker per core busy at the tests' own priority; at the end a table
says, per test, in how many rounds it failed. Exit status 1 when any round had a failure.

    scripts/stress.sh --repeat 3          (make test-stress REPEAT=3)
    scripts/stress.sh -k lab1 --repeat 5  (a subset, as run_tests.py -k)
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import course_testing

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(REPO, 'build', 'test-results')
OUT = os.path.join(REPO, 'build', 'stress')


def one_round(k, args, env):
    """Run the suite once; returns its summary dict (failures, counts, seconds)."""
    cmd = [sys.executable, os.path.join(REPO, 'scripts', 'run_tests.py')]
    if args.full:
        cmd.append('--full')
    if args.keyword:
        cmd += ['-k', args.keyword]
    log = os.path.join(OUT, 'round-%d.log' % k)
    summary_path = os.path.join(RESULTS, 'summary.json')
    if os.path.exists(summary_path):
        os.remove(summary_path)
    t = time.monotonic()
    with open(log, 'w') as fh:
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env, cwd=REPO)
        try:
            for line in p.stdout:       # the round's progress on the terminal and in its log
                fh.write(line)
                fh.flush()
                if line.startswith(('===', 'FAILED', '    FAILED')) or 'passed,' in line:
                    print('  [%d] %s' % (k, line.rstrip()), flush=True)
            p.wait()
        except BaseException:
            # stopped (Ctrl-C, SIGTERM): run_tests.py stops its tests and their processes
            p.terminate()
            try:
                p.wait(180)
            except subprocess.TimeoutExpired:
                p.kill()
            raise
    try:
        with open(summary_path) as fh:
            summary = json.load(fh)
    except (OSError, ValueError):
        summary = {'passed': 0, 'failed': 1, 'skipped': 0, 'durations': [],
                   'failures': ['run_tests.py exited %s without a summary (see %s)' % (p.returncode, log)]}
    summary['wall'] = time.monotonic() - t
    shutil.copy(summary_path, os.path.join(OUT, 'round-%d.json' % k)) if os.path.exists(summary_path) else None
    return summary


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--repeat', type=int, default=1, help='rounds (default 1)')
    ap.add_argument('--workers', type=int, default=None, help='CPU workers (default: one per core)')
    ap.add_argument('--full', action='store_true', help='also the slow tests (make test-full)')
    ap.add_argument('-k', dest='keyword', help='as run_tests.py -k')
    args = ap.parse_args()

    def stop(signum, _frame):
        # SIGTERM unwinds as Ctrl-C does: the running round and the CPU load are stopped
        raise KeyboardInterrupt('stress: signal %d' % signum)
    signal.signal(signal.SIGTERM, stop)
    os.makedirs(OUT, exist_ok=True)
    # no subreaper or orphan reaping here: run_tests.py reaps what each test leaves behind, and
    # reaping every descendant of this process would kill the CPU load itself
    env = dict(os.environ, PYTHONUNBUFFERED='1')    # the round's log fills as it runs
    rounds = []
    with course_testing.cpu_load(args.workers) as load:
        print('=== stress: %d CPU workers (stress-ng) on %d cores, %d round(s)' % (
            load.workers, os.cpu_count(), args.repeat), flush=True)
        for k in range(1, args.repeat + 1):
            print('=== round %d of %d' % (k, args.repeat), flush=True)
            if load.busy_workers() < load.workers:
                raise SystemExit('stress: the CPU load died before round %d' % k)
            r = one_round(k, args, env)
            r['load_alive'] = load.busy_workers() >= load.workers
            rounds.append(r)

    print('\n=== stress summary (%d CPU workers)' % load.workers)
    print('round   time     passed  failed  load kept up')
    for k, r in enumerate(rounds, 1):
        print('%5d %6.0f s %9d %7d  %s' % (k, r['wall'], r['passed'], r['failed'],
                                           'yes' if r['load_alive'] else 'NO'))
    count = {}
    for r in rounds:
        for name in r['failures']:
            count[name] = count.get(name, 0) + 1
    if count:
        print('\nfailed in how many of %d rounds:' % len(rounds))
        for name, n in sorted(count.items(), key=lambda kv: (-kv[1], kv[0])):
            print('  %d/%d  %s' % (n, len(rounds), name))
    bad = sum(1 for r in rounds if r['failed'])
    print('%d of %d rounds had failures' % (bad, len(rounds)))
    total_p = sum(r['passed'] for r in rounds)
    total_f = sum(r['failed'] for r in rounds)
    print('%d passed, %d failed' % (total_p, total_f), flush=True)
    return 1 if total_f or not all(r['load_alive'] for r in rounds) else 0


if __name__ == '__main__':
    sys.exit(main())
