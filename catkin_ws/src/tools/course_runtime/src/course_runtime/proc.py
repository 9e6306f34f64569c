"""Process handling: every child runs in its own process group and is stopped by PID.

roslaunch/rostest start their nodes in sessions of their own, so signalling a process group
is not enough to stop a launch that hangs: `run` and `Proc.stop` also remember the whole
process tree and kill what is left of it, and `become_subreaper` lets a long-lived parent
(the test runner, labs/grade) collect orphans that escaped every group.
"""
import contextlib
import ctypes
import os
import signal
import socket
import subprocess
import time

PR_SET_CHILD_SUBREAPER = 36


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


def _proc_table():
    """{pid: (ppid, starttime)} of every process now."""
    table = {}
    for name in os.listdir('/proc'):
        if not name.isdigit():
            continue
        try:
            with open('/proc/%s/stat' % name) as f:
                fields = f.read().rsplit(')', 1)[1].split()
            table[int(name)] = (int(fields[1]), fields[19])
        except (OSError, IndexError, ValueError):
            continue
    return table


def descendants(root):
    """{pid: starttime} of every live descendant of `root` (not root itself)."""
    table = _proc_table()
    children = {}
    for pid, (ppid, _) in table.items():
        children.setdefault(ppid, []).append(pid)
    found, todo = {}, [root]
    while todo:
        for c in children.get(todo.pop(), ()):
            if c not in found:
                found[c] = table[c][1]
                todo.append(c)
    return found


def kill_remembered(procs):
    """SIGKILL each remembered {pid: starttime} that is still the same process."""
    table = _proc_table()
    for pid, start in procs.items():
        if table.get(pid, (None, None))[1] == start:
            try:
                os.kill(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass


def become_subreaper():
    """Orphaned descendants are re-parented to this process instead of init (Linux)."""
    try:
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
    except (OSError, AttributeError):
        pass


def reap_orphans(keep=()):
    """Kill every remaining descendant of this process and reap it; returns their commands.
    `keep`: pids of children still running (another lane of a concurrent test run) whose
    process trees are left alone."""
    left = descendants(os.getpid())
    for pid in keep:
        left.pop(pid, None)
        for child in descendants(pid):
            left.pop(child, None)
    names = []
    for pid in left:
        try:
            with open('/proc/%d/cmdline' % pid, 'rb') as f:
                names.append(f.read().replace(b'\0', b' ').decode(errors='replace').strip()[:120])
        except OSError:
            pass
    kill_remembered(left)
    for pid in left:
        try:
            os.waitpid(pid, 0)
        except (ChildProcessError, OSError):
            pass
    return [n for n in names if n]


def stop_tree(popen, first=signal.SIGINT, grace=10.0):
    """Stop popen's process group gently (first, then SIGTERM), then SIGKILL the group and
    every process of its tree seen on the way, even those in other sessions."""
    tree = {}
    for sig, t in ((first, grace), (signal.SIGTERM, 3.0)):
        if popen.poll() is not None:
            break
        tree.update(descendants(popen.pid))
        try:
            os.killpg(popen.pid, sig)
        except ProcessLookupError:
            break
        try:
            popen.wait(t)
        except subprocess.TimeoutExpired:
            continue
    tree.update(descendants(popen.pid))
    try:
        os.killpg(popen.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    kill_remembered(tree)
    try:
        popen.wait(3.0)
    except subprocess.TimeoutExpired:
        pass
    return popen.poll()


def run(cmd, timeout, env=None, cwd=None, log=None, started=None, lock=None):
    """Run cmd in its own process group, output to the file `log` (or inherited when None).
    On timeout stop its whole tree. Returns (exit code or None, timed_out).
    A concurrent runner passes `started(popen)`, called under `lock` together with the process's
    creation, so that its orphan reaper (holding the same lock) never sees an unregistered child."""
    out = open(log, 'wb') if log else None
    with lock if lock is not None else contextlib.nullcontext():
        p = subprocess.Popen(cmd, env=env, cwd=cwd, stdout=out,
                             stderr=subprocess.STDOUT if out else None,
                             stdin=subprocess.DEVNULL, start_new_session=True)
        if started:
            started(p)
    try:
        try:
            return p.wait(timeout), False
        except subprocess.TimeoutExpired:
            stop_tree(p)
            return None, True
    finally:
        if p.poll() is not None:
            try:
                os.killpg(p.pid, signal.SIGKILL)   # stragglers left in its group
            except (ProcessLookupError, PermissionError):
                pass
        if out:
            out.close()


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
        """Signal the process group (sig, then SIGTERM), then SIGKILL the group and the rest of
        its tree (nodes of a roslaunch live in sessions of their own); return the exit code."""
        rc = stop_tree(self.popen, sig, timeout)
        if self._log:
            self._log.close()
            self._log = None
        return rc

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


def start(cmd, **kwargs):
    return Proc(cmd, **kwargs)
