"""How fast the demo's simulation ran and what the stack cost, per phase (no ROS here).

PhaseMeter takes the simulated time, the wall clock and the CPU time of every process of a
launch (roslaunch and all its descendants, read from /proc) at the start of a phase and at any
later moment, and gives the achieved real-time factor (simulated seconds per wall second) and
the stack's CPU seconds per simulated second, with the busiest processes. The CPU figure does
not depend on how loaded the machine is: at 1.0x real time the stack needs that many cores.
The clocks and the process table are injectable, so the arithmetic is tested without a
simulation."""
import os
import time

TICK = os.sysconf('SC_CLK_TCK')


def _stat(pid, proc='/proc'):
    """(name, parent pid, CPU seconds: user + system) of one process, from /proc/PID/stat."""
    return read_stat('%s/%d/stat' % (proc, pid))


def read_stat(path):
    """(name, parent pid, CPU seconds: user + system) from a stat file: /proc/PID/stat or a
    thread's /proc/PID/task/TID/stat (bench/sim_rtf reads both)."""
    with open(path) as f:
        text = f.read()
    comm = text[text.index('(') + 1:text.rindex(')')]
    fields = text.rsplit(')', 1)[1].split()
    return comm, int(fields[1]), (int(fields[11]) + int(fields[12])) / TICK


def node_name(pid, comm, proc='/proc'):
    """The ROS node name (__name:=) of a process, else its program's name."""
    try:
        with open('%s/%d/cmdline' % (proc, pid), 'rb') as f:
            argv = [a.decode('utf-8', 'replace') for a in f.read().split(b'\0') if a]
    except OSError:
        return comm
    for a in argv:
        if a.startswith('__name:='):
            return a[len('__name:='):]
    if len(argv) > 1 and os.path.basename(argv[0]).startswith('python'):
        return os.path.basename(argv[1])
    return os.path.basename(argv[0]) if argv else comm


def process_tree_cpu(root, proc='/proc'):
    """{pid: (name, CPU seconds)} of `root` and all its descendants (a roslaunch and its nodes:
    each node runs in a session of its own but stays roslaunch's child)."""
    table = {}
    for d in os.listdir(proc):
        if d.isdigit():
            try:
                table[int(d)] = _stat(int(d), proc)
            except (OSError, ValueError):
                continue
    children = {}
    for pid, (_, ppid, _) in table.items():
        children.setdefault(ppid, []).append(pid)
    out, todo = {}, [root]
    while todo:
        pid = todo.pop()
        if pid in table and pid not in out:
            out[pid] = (node_name(pid, table[pid][0], proc), table[pid][2])
            todo += children.get(pid, [])
    return out


class PhaseMeter:
    """One phase of the demo: start() at its beginning, figures() at any time after.

    sim_now: simulated seconds (rospy.get_time); wall_now: wall seconds; tree: root pid ->
    {pid: (name, CPU s)} (process_tree_cpu)."""

    def __init__(self, sim_now, wall_now=time.monotonic, tree=process_tree_cpu):
        self.sim_now, self.wall_now, self.tree = sim_now, wall_now, tree
        self.root = None
        self.start_point = None

    def _point(self):
        return self.sim_now(), self.wall_now(), self.tree(self.root) if self.root else {}

    def start(self, root_pid):
        self.root = root_pid
        self.start_point = self._point()
        return self.start_point

    def figures(self, since=None):
        """Since the start (or since an earlier point of this meter): dict with sim_s, wall_s,
        rtf (simulated per wall second), cpu_s (all processes of the tree, including those
        started meanwhile; those that ended are not counted), cpu_per_sim_s and top (the
        processes by CPU seconds, busiest first)."""
        s0, w0, t0 = since if since is not None else self.start_point
        s1, w1, t1 = now = self._point()
        per = {}
        for pid, (name, cpu) in t1.items():
            used = cpu - t0[pid][1] if pid in t0 else cpu
            per[name] = per.get(name, 0.0) + max(0.0, used)
        sim, wall = s1 - s0, w1 - w0
        cpu = sum(per.values())
        return {'sim_s': sim, 'wall_s': wall, 'rtf': sim / wall if wall > 0 else 0.0,
                'cpu_s': cpu, 'cpu_per_sim_s': cpu / sim if sim > 0 else float('nan'),
                'top': sorted(per.items(), key=lambda kv: -kv[1]), 'point': now}


def describe(name, f, top=4):
    """One line: '<name>: 0.98x real time (120 s simulated in 122 s), the stack 0.61 CPU s per
    simulated s (gazebo 0.25, move_base 0.12, ...)'."""
    busiest = ', '.join('%s %.2f' % (n, c / f['sim_s']) for n, c in f['top'][:top]
                        if f['sim_s'] > 0)
    tail = ' (%s)' % busiest if busiest else ''
    return ('%s: %.2fx real time (%.0f s simulated in %.0f s of wall time), the stack %.2f CPU s '
            'per simulated s%s' % (name, f['rtf'], f['sim_s'], f['wall_s'], f['cpu_per_sim_s'], tail))
