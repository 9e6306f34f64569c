"""Process handling: every child runs in its own process group and is stopped by PID."""
import os
import signal
import socket
import subprocess
import time


def free_port():
    """A TCP port that was free a moment ago (bound to port 0 and released)."""
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def wait_for(predicate, timeout, interval=0.05, what='condition'):
    """Poll predicate() until it returns a truthy value; raise TimeoutError naming `what`."""
    deadline = time.monotonic() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError('timed out after %.1f s waiting for %s' % (timeout, what))
        time.sleep(interval)


class Proc:
    """A child process in its own process group; output goes to a log file or a pipe."""

    def __init__(self, cmd, env=None, cwd=None, log=None, stdin=None, stdout=None, pass_fds=()):
        self.cmd = cmd
        self.log_path = log
        self._log = open(log, 'wb') if log else None
        out = self._log if self._log else (stdout if stdout is not None else subprocess.DEVNULL)
        self.popen = subprocess.Popen(
            cmd, env=env, cwd=cwd, stdin=stdin if stdin is not None else subprocess.DEVNULL,
            stdout=out, stderr=subprocess.STDOUT if out is not subprocess.DEVNULL else out,
            start_new_session=True, pass_fds=pass_fds)
        self.pid = self.popen.pid

    def alive(self):
        return self.popen.poll() is None

    def output(self):
        """Text logged so far (only when started with log=...)."""
        if not self.log_path:
            return ''
        if self._log:
            self._log.flush()
        with open(self.log_path, 'rb') as f:
            return f.read().decode('utf-8', 'replace')

    def stop(self, sig=signal.SIGINT, timeout=10.0):
        """Signal the whole process group, escalate to SIGTERM then SIGKILL; return exit code."""
        for s, t in ((sig, timeout), (signal.SIGTERM, 3.0), (signal.SIGKILL, 3.0)):
            if self.popen.poll() is not None:
                break
            try:
                os.killpg(self.pid, s)
            except ProcessLookupError:
                break
            try:
                self.popen.wait(t)
            except subprocess.TimeoutExpired:
                continue
        # children left in the group (e.g. nodes of a roslaunch) are killed too
        try:
            os.killpg(self.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        if self._log:
            self._log.close()
            self._log = None
        return self.popen.poll()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


def start(cmd, **kwargs):
    return Proc(cmd, **kwargs)
