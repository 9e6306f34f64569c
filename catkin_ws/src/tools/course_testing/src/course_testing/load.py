"""A saturated CPU for tests and `make test-stress`: Debian's stress-ng, one busy worker per core.

    with cpu_load():          # every core busy while the block runs
        ...

The workers run at the tests' own priority (nice 0), so a test gets about half of each core:
what a student's laptop compiling in the background, or a shared CI runner, gives it.
"""
import os
import shutil
import signal
import subprocess
import time
from contextlib import contextmanager

from course_runtime.proc import stop_tree


class CpuLoad:
    """stress-ng --cpu N (N = cores by default) in a process group of its own."""

    def __init__(self, workers=None, method='matrixprod'):
        self.workers = workers or os.cpu_count() or 1
        self.method = method
        self.popen = None

    def start(self):
        exe = shutil.which('stress-ng')
        if exe is None:
            raise RuntimeError('stress-ng is not installed (Debian package stress-ng, in deps/debian.txt): '
                               'run scripts/setup.sh')
        self.popen = subprocess.Popen(
            [exe, '--cpu', str(self.workers), '--cpu-method', self.method, '--quiet'],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            start_new_session=True)
        deadline = time.monotonic() + 10.0     # the workers are up when they use CPU time
        while time.monotonic() < deadline:
            if self.popen.poll() is not None:
                raise RuntimeError('stress-ng exited at once: %s' % self.popen.stderr.read().decode()[-300:])
            if self.busy_workers() >= self.workers:
                return self
            time.sleep(0.1)
        raise RuntimeError('stress-ng did not start %d workers within 10 s' % self.workers)

    def busy_workers(self):
        """Number of this load's processes (the stress-ng parent excluded)."""
        try:
            out = subprocess.run(['ps', '-o', 'pid=', '--ppid', str(self.popen.pid)],
                                 stdout=subprocess.PIPE, text=True).stdout
        except OSError:
            return 0
        return len(out.split())

    def stop(self):
        if self.popen is not None:
            stop_tree(self.popen, signal.SIGTERM, 5.0)
            if self.popen.stderr:
                self.popen.stderr.close()
            self.popen = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


@contextmanager
def cpu_load(workers=None):
    load = CpuLoad(workers)
    load.start()
    try:
        yield load
    finally:
        load.stop()
