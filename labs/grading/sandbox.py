"""The grading sandbox: the student's build and nodes run under bubblewrap (Debian's `bwrap`).

Why bubblewrap and not the course Docker image: a grading starts a dozen short processes (the
build, a roslaunch) that must reach the grader's ROS master and share its loopback; bwrap wraps
each of them in a few milliseconds without a daemon, an image or root-owned state to clean up,
and Debian ships it (0.8.0). What a sandboxed process gets (`Sandbox.wrap`):

- own mount, PID, IPC and UTS namespaces (`--unshare-pid --unshare-ipc --unshare-uts`), dies
  with the grader (`--die-with-parent`);
- a file system of /usr, /etc and the course tree read-only; the labs folder (reference
  solutions, graders), every other path of the machine (other submissions, the grader's work
  folder and report) invisible; a private /tmp (tmpfs, bounded size) as HOME and ROS_HOME;
  the student's overlay workspace writable only while it builds (it lives on a tmpfs of bounded
  size mounted by the grader);
- a user of its own (uid 60000 + n, no capabilities, no_new_privs), limits (`prlimit`) on the
  number of processes of that user, address space, CPU time per process and file size;
- the network of the grading it belongs to: `netns_prefix()` puts the whole grading (master,
  checker, student) in a network namespace with only a loopback, so parallel gradings cannot
  see each other's masters and nothing leaves the machine.

The checker and the master run outside the sandbox; the verdict comes only from the checker.
"""
import json
import os
import random
import shutil
import subprocess
import time

from course_runtime import SOFTWARE_GL
from grading.common import LABS_DIR

REPO = os.path.dirname(LABS_DIR)
ENV_VAR = 'GRADING_SANDBOX'
LIMITS = {'nproc': 1024,           # tasks (threads count) of the sandbox's user
          'as_mb': 6144,           # address space per process
          'cpu_s': 900,            # CPU time per process
          'fsize_mb': 256,         # largest file
          'tmp_mb': 256,           # the private /tmp
          'ws_mb': 1024,           # the overlay workspace (build + devel)
          'procs': 256}            # processes at once: more is a fork bomb, the sandbox is stopped
SYSTEM_RO = ('/usr', '/etc')
SYMLINKS = (('usr/bin', '/bin'), ('usr/lib', '/lib'), ('usr/lib64', '/lib64'), ('usr/sbin', '/sbin'))


def probe():
    """None when a sandbox can be made here, else a one-line reason."""
    for tool in ('bwrap', 'setpriv', 'prlimit', 'unshare'):
        if not shutil.which(tool):
            return '%s is not installed (Debian package %s)' % (
                tool, {'bwrap': 'bubblewrap'}.get(tool, 'util-linux'))
    test = Sandbox(uid=60000 + os.getpid() % 5000, ws=None)
    try:
        r = subprocess.run(netns_prefix() + test.wrap(['true']), stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=30)
    except (OSError, subprocess.TimeoutExpired) as e:
        return 'bwrap did not run: %s' % e
    if r.returncode != 0:
        lines = [l for l in r.stdout.decode(errors='replace').splitlines() if l.strip()]
        return (lines[-1] if lines else 'bwrap failed with exit code %d' % r.returncode)[:200]
    return None


def netns_prefix():
    """Run a command in a new network namespace with only its loopback up."""
    return ['unshare', '--net', '--', 'sh', '-c', 'ip link set lo up && exec "$@"', 'grading-netns']


def new_uid():
    return 60000 + random.randrange(5000)


class Sandbox:
    def __init__(self, uid, ws, hide=(), limits=None, student_env=None):
        self.uid = int(uid)
        self.ws = ws
        self.hide = [h for h in hide if h]
        self.limits = dict(LIMITS, **(limits or {}))
        self.student_env = student_env   # the overlay's environment (the checker's own is the course's)

    def to_json(self):
        return json.dumps({'uid': self.uid, 'ws': self.ws, 'hide': self.hide, 'limits': self.limits,
                           'env': self.student_env})

    @classmethod
    def from_json(cls, text):
        d = json.loads(text)
        return cls(d['uid'], d.get('ws'), d.get('hide', ()), d.get('limits'), d.get('env'))

    @classmethod
    def from_env(cls, env=None):
        text = (env if env is not None else os.environ).get(ENV_VAR)
        return cls.from_json(text) if text else None

    def wrap(self, cmd, writable_ws=False, cwd='/tmp'):
        lim = self.limits
        a = ['bwrap', '--unshare-pid', '--unshare-ipc', '--unshare-uts', '--die-with-parent',
             '--hostname', 'sandbox']
        for d in SYSTEM_RO:
            a += ['--ro-bind', d, d]
        for target, link in SYMLINKS:
            if os.path.islink(link):
                a += ['--symlink', target, link]
            elif os.path.isdir(link):
                a += ['--ro-bind', link, link]
        # the private /tmp first: a course tree (or workspace) under /tmp is bound on top of it
        a += ['--size', str(lim['tmp_mb'] << 20), '--perms', '1777', '--tmpfs', '/tmp',
              '--perms', '0777', '--dir', '/tmp/home']
        d, parents = os.path.dirname(REPO), []
        while d not in ('/', '/tmp'):
            parents.insert(0, d)
            d = os.path.dirname(d)
        for d in parents:          # bwrap makes missing parents 0700: the sandbox's user must pass
            a += ['--perms', '0755', '--dir', d]
        a += ['--ro-bind', REPO, REPO]
        hidden = []
        for h in sorted(set(os.path.realpath(x) for x in [LABS_DIR] + self.hide), key=len):
            if (os.path.isdir(h) and (h + '/').startswith(REPO + '/') and h != REPO
                    and not any((h + '/').startswith(x + '/') for x in hidden)):
                hidden.append(h)
                a += ['--tmpfs', h, '--remount-ro', h]
        if self.ws:
            parents, d = [], os.path.dirname(self.ws)
            while d.startswith('/tmp/'):
                parents.insert(0, d)
                d = os.path.dirname(d)
            for d in parents:          # traversable by the sandbox's user (the grader's are 0700)
                a += ['--perms', '0755', '--dir', d]
            a += ['--bind' if writable_ws else '--ro-bind', self.ws, self.ws]
        a += ['--dev', '/dev', '--proc', '/proc', '--chdir', cwd, '--']
        a += ['setpriv', '--reuid', str(self.uid), '--regid', str(self.uid), '--clear-groups',
              '--inh-caps=-all', '--bounding-set=-all', '--no-new-privs', '--']
        a += ['prlimit', '--nproc=%d' % lim['nproc'], '--as=%d' % (lim['as_mb'] << 20),
              '--cpu=%d' % lim['cpu_s'], '--fsize=%d' % (lim['fsize_mb'] << 20), '--core=0', '--']
        return a + list(cmd)

    def env(self, env):
        """The environment of a sandboxed process: no grader variables or paths, HOME and
        ROS_HOME in the private /tmp."""
        if self.student_env:
            # the student's own overlay environment; only the master's address from the caller
            keep = {k: env[k] for k in ('ROS_MASTER_URI', 'ROS_IP', 'DISPLAY', 'QT_QPA_PLATFORM',
                                        *SOFTWARE_GL) if k in env}
            env = dict(self.student_env, **keep)
            for k in ('DISPLAY', 'QT_QPA_PLATFORM'):   # the caller's say, not the overlay's
                if k not in keep:
                    env.pop(k, None)
        env = {k: v for k, v in env.items() if not k.startswith('GRADING_')}
        for var in ('ROS_PACKAGE_PATH', 'PYTHONPATH', 'CMAKE_PREFIX_PATH'):
            if var in env:
                parts = [p for p in env[var].split(':') if p and not (p + '/').startswith(LABS_DIR + '/')]
                env[var] = ':'.join(parts)
        env.update(HOME='/tmp/home', ROS_HOME='/tmp/ros', ROS_LOG_DIR='/tmp/ros/log',
                   CCACHE_DISABLE='1', TMPDIR='/tmp', USER='student', LOGNAME='student')
        env.pop('XAUTHORITY', None)
        return env

    def prepare_ws(self, ws):
        """A bounded tmpfs for the overlay workspace, owned by the sandbox's user (root only;
        elsewhere a plain folder). Returns True when a mount was made."""
        os.makedirs(ws, exist_ok=True)
        mounted = False
        if os.geteuid() == 0:
            r = subprocess.run(['mount', '-t', 'tmpfs', '-o', 'size=%dm,mode=0755,uid=%d,gid=%d'
                                % (self.limits['ws_mb'], self.uid, self.uid), 'grading-ws', ws],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            mounted = r.returncode == 0
        return mounted

    def chown_tree(self, root):
        if os.geteuid() != 0:
            return
        for d, dirs, files in os.walk(root):
            for n in [d] + [os.path.join(d, f) for f in dirs + files]:
                try:
                    os.lchown(n, self.uid, self.uid)
                except OSError:
                    pass


def release_ws(ws):
    """Unmount the workspace tmpfs made by prepare_ws (lazily, if still busy)."""
    if os.path.ismount(ws):
        subprocess.run(['umount', '-l', ws], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


# --- pids of sandboxed processes, seen from outside ----------------------------------------
# Only /proc/PID/status (PPid, NSpid) is read: it is world-readable, whereas the namespace
# links /proc/PID/ns/* need ptrace access to the process, which root in a Docker container
# (no CAP_SYS_PTRACE) lacks for the sandbox user's processes — there the grader saw none of
# the student's nodes (lab 3: "no robot_state_publisher ... running") and counted no fork bomb.

_sandbox = {'init': None}


def _status(pid):
    """(ppid, NSpid list) of process `pid` from /proc/PID/status, or None when it is gone."""
    ppid, nspid = None, None
    try:
        with open('/proc/%s/status' % pid) as f:
            for line in f:
                if line.startswith('PPid:'):
                    ppid = int(line.split()[1])
                elif line.startswith('NSpid:'):
                    nspid = [int(x) for x in line.split()[1:]]
    except (OSError, ValueError):
        return None
    if ppid is None or not nspid:
        return None
    return ppid, nspid


def _processes():
    """{pid: (ppid, NSpid)} of every process in /proc."""
    table = {}
    for entry in os.listdir('/proc'):
        if entry.isdigit():
            st = _status(entry)
            if st:
                table[int(entry)] = st
    return table


def _members(table, init):
    """PIDs (in our namespace) of `init` and all its descendants in `table`."""
    children = {}
    for pid, (ppid, _) in table.items():
        children.setdefault(ppid, []).append(pid)
    out, todo = [], ([init] if init in table else [])
    while todo:
        pid = todo.pop()
        out.append(pid)
        todo.extend(children.get(pid, ()))
    return out


def pidns_of_child(pid):
    """The sandbox started as process `pid` (bwrap), named by the PID (in our namespace) of its
    first process in a PID namespace of its own — bwrap's child, the sandbox's PID 1; None when
    none appears within 5 s."""
    mine = _status(os.getpid())
    depth = len(mine[1]) if mine else 1
    for _ in range(50):
        for child, (ppid, nspid) in _processes().items():
            if ppid == pid and len(nspid) > depth:
                return child
        time.sleep(0.1)
    return None


def remember_pidns(init):
    if init:
        _sandbox['init'] = init


def host_pid(pid):
    """The PID in our namespace of the process that a node inside the current sandbox reports
    as `pid` (getPid), or the pid itself when no sandbox is in use; None when it is gone."""
    init = _sandbox['init']
    if not init:
        return pid
    table = _processes()
    for member in _members(table, init):
        if table[member][1][-1] == pid:
            return member
    return None


def count_procs(init):
    """How many processes the sandbox named `init` (pidns_of_child) holds."""
    return len(_members(_processes(), init))
