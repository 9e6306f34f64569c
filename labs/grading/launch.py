"""The rospy side shared by every lab's observer: the student's processes, the master, a launch.

A lab's observer (grading.labN.observer) starts the student's nodes or launch file as `Child`
processes (inside the grading sandbox when labs/grade made one), watches the master through
`GraphWatcher` or `master_round`, and polls with `poll` until it has seen enough. Time stamps
are wall seconds (time.monotonic) so that a stalled node cannot stall the clock.
"""
import os
import re
import signal
import subprocess
import threading
import time
import xmlrpc.client

import rosgraph
import roslib.message
import rospy
from course_runtime import stop_tree

from grading import sandbox

IGNORED_NODES = ('/rosout',)


def numeric(msg):
    """The number in a std_msgs-like message (`data` field), or None."""
    v = getattr(msg, 'data', None)
    if isinstance(v, bool):
        return float(v)
    if isinstance(v, (int, float)):
        return float(v)
    if hasattr(v, 'to_sec'):
        return float(v.to_sec())
    return None


def _lines(path):
    """The non-empty lines of a log, stripped; None when it cannot be read."""
    try:
        with open(path, errors='replace') as f:
            return [l.strip() for l in f.read().splitlines() if l.strip()]
    except OSError:
        return None


def last_line(path):
    lines = _lines(path)
    if lines is None:
        return ''
    return lines[-1][:200] if lines else '(no output)'


def plain(text):
    """Text without terminal colour codes and control characters (they break JUnit XML)."""
    text = re.sub(r'\x1b\[[0-9;]*[A-Za-z]|\x1b\][^\x07]*\x07', '', text)
    return ''.join(ch for ch in text if ch >= ' ' or ch == '\t')


def launch_failure(log):
    """The telling line of a failed roslaunch's output."""
    lines = _lines(log)
    if lines is None:
        return 'roslaunch failed (no output)'
    lines = [plain(l).strip() for l in lines]
    for key in ('RLException', 'ResourceNotFound', 'Resource not found', 'ERROR', 'Error', 'error'):
        for l in lines:
            if key in l:
                return l[:250]
    return (lines[-1] if lines else 'no output')[:250]


def error_line(text, keys):
    """The first line of a tool's output that carries one of `keys`, else its last line."""
    lines = [plain(l).strip() for l in text.splitlines() if plain(l).strip()]
    for k in keys:
        for l in lines:
            if k in l:
                return l[:250]
    return (lines[-1] if lines else 'failed without output')[:250]


class Child:
    """A student process in its own process group, output logged."""

    def __init__(self, cmd, log, env=None):
        self.log = log
        self._out = open(log, 'wb')
        env = dict(os.environ if env is None else env)
        box = sandbox.Sandbox.from_env(env)
        if box is not None:     # labs/grade asked for the student's processes to be sandboxed
            cmd = box.wrap(cmd)
            env = box.env(env)
        self.p = subprocess.Popen(cmd, stdout=self._out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                  env=env, start_new_session=True)
        self.killed_for = None
        if box is not None:
            ns = sandbox.pidns_of_child(self.p.pid)
            sandbox.remember_pidns(ns)
            if ns:
                threading.Thread(target=self._watch, args=(ns, box.limits['procs']), daemon=True).start()

    def _watch(self, ns, limit):
        """Stop the sandbox when its processes reach `limit` (a fork bomb), so that it fails
        its own run quickly and nothing else."""
        while self.p.poll() is None:
            n = sandbox.count_procs(ns)
            if n >= limit:
                self.killed_for = ('stopped by the grader: the sandbox reached its process limit '
                                   '(%d processes at once; a fork bomb?)' % n)
                stop_tree(self.p, first=signal.SIGKILL, grace=2.0)
                return
            time.sleep(0.5)

    def rc(self):
        return self.p.poll()

    def stop(self):
        stop_tree(self.p, grace=8.0)
        self._out.close()


def poll(step, period):
    """Call step(time.monotonic()) every `period` s until it returns a reason to stop; returns
    that reason, or None when ROS shuts down first."""
    while not rospy.is_shutdown():
        why = step(time.monotonic())
        if why:
            return why
        time.sleep(period)
    return None


class Launch:
    """`roslaunch` of the student's launch file as a Child; its log is logdir/roslaunch.log."""

    def __init__(self, cmd, logdir, pkg_dir, env=None):
        self.cmd = cmd
        self.log = os.path.join(logdir, 'roslaunch.log')
        self.pkg_dir = pkg_dir
        self.start = time.monotonic()
        self.child = Child(cmd, self.log, env=env)

    def exited(self):
        return self.child.rc() is not None

    def failure(self, relative=True):
        """Why the launch ended: the sandbox's stop or the telling line of its log (package
        paths shown relative to the package unless `relative` is False)."""
        text = plain(self.child.killed_for or launch_failure(self.log))
        return text.replace(self.pkg_dir.rstrip('/') + '/', '') if relative else text

    def stop(self):
        self.child.stop()


def read_description(master, res):
    """Store /robot_description in res['robot_description'] once the parameter is set."""
    if res.get('robot_description') is None and master.hasParam('/robot_description'):
        v = master.getParam('/robot_description')
        res['robot_description'] = v if isinstance(v, str) else str(v)


def master_round(master, res):
    """One look at the master: /robot_description into `res` (once), and the system state
    [publishers, subscribers, services]; None while the master is busy or not up yet."""
    try:
        read_description(master, res)
        return master.getSystemState()
    except Exception:   # master busy or not up yet: next round
        return None


def graph_nodes(state):
    """Every node named in a system state (None: none)."""
    nodes = set()
    for table in state or ():
        for _name, ns in table:
            nodes.update(ns)
    return nodes


class GraphWatcher:
    """Accumulates the master's system state; subscribes to topics on request."""

    def __init__(self):
        self.me = rospy.get_name()
        self.master = rosgraph.Master(self.me)
        self.nodes = set()
        self.pubs, self.subs, self.srvs = {}, {}, {}
        self.types = {}
        self.msgs = {}
        self._subscribed = {}
        self.lock = threading.Lock()

    def poll(self):
        try:
            pubs, subs, srvs = self.master.getSystemState()
            types = dict(self.master.getTopicTypes())
        except Exception:   # master busy: try again next poll
            return False
        self.types.update(types)
        for table, dest in ((pubs, self.pubs), (subs, self.subs), (srvs, self.srvs)):
            for name, nodes in table:
                for n in nodes:
                    if n == self.me or n in IGNORED_NODES:
                        continue
                    self.nodes.add(n)
                    dest.setdefault(n, set()).add(name)
        return True

    def listen(self, topic, convert=numeric, cls=None):
        """Record (t, convert(msg)) of a topic; type looked up from the master unless given."""
        if topic in self._subscribed:
            return True
        if cls is None:
            t = self.types.get(topic)
            cls = roslib.message.get_message_class(t) if t else None
            if cls is None:
                return False
        self.msgs.setdefault(topic, [])

        def cb(msg, topic=topic):
            v = convert(msg)
            if v is not None:
                with self.lock:
                    self.msgs[topic].append((time.monotonic(), v))
        self._subscribed[topic] = rospy.Subscriber(topic, cls, cb, queue_size=100)
        return True

    def series(self, topic):
        with self.lock:
            return list(self.msgs.get(topic, []))

    def state(self):
        return {'nodes': sorted(self.nodes),
                'pubs': {n: sorted(t) for n, t in self.pubs.items()},
                'subs': {n: sorted(t) for n, t in self.subs.items()},
                'srvs': {n: sorted(t) for n, t in self.srvs.items()},
                'types': dict(self.types)}


def node_process(master, node):
    """(host PID, command line) of a ROS node (its PID over XML-RPC), or (None, [])."""
    try:
        uri = master.lookupNode(node)
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid(rospy.get_name())
        pid = sandbox.host_pid(pid)     # a sandboxed node reports its pid in the sandbox's namespace
        if pid is None:
            return None, []
        return pid, process_argv(pid)
    except Exception:   # node gone or not answering: not counted
        return None, []


def node_argv(master, node):
    """The command line of a ROS node (from its PID over XML-RPC), or []."""
    return node_process(master, node)[1]


def process_argv(pid):
    """The command line of process `pid`, or [] when it is gone."""
    try:
        with open('/proc/%d/cmdline' % pid, 'rb') as f:
            return [a.decode(errors='replace') for a in f.read().split(b'\0') if a]
    except OSError:
        return []
