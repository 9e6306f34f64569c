"""Lab 1's observer (rospy): start node1..3 of the student's package, watch numbers and the result."""
import os
import time

from grading.launch import Child, GraphWatcher, last_line, poll
from grading.lab1 import rules
from grading.lab1.variants import NODES, roles


class Lab1Observer:
    """Start node1..3 of the student's package, watch numbers and the result."""

    def __init__(self, isu, scripts, logdir):
        self.isu = isu
        self.scripts = scripts      # {'node1.py': path, ...}
        self.logdir = logdir
        self.graph = GraphWatcher()
        self.children = {}
        self.first_result = None
        self.first_exit = None      # when a node was first seen to have exited
        self.nodes_seen = (frozenset(), None)   # the graph's nodes, and since when

    def _start(self):
        """Start every executable node script; returns the scripts that are not executable."""
        not_exec = [n + '.py' for n in NODES
                    if n + '.py' in self.scripts and not os.access(self.scripts[n + '.py'], os.X_OK)]
        for n in NODES:
            path = self.scripts.get(n + '.py')
            if path and n + '.py' not in not_exec:
                self.children[n] = Child([path, '_isu:=%s' % self.isu], os.path.join(self.logdir, n + '.log'))
        return not_exec

    def _step(self, now, start, comp):
        """One round: listen to every student topic; a reason to stop, or None."""
        self.graph.poll()
        for topic, _node in self._student_topics():
            self.graph.listen(topic)
        wanted = rules.result_topics(self.isu, comp)
        res = [t for t in wanted if self.graph.series(t)]
        if res and self.first_result is None:
            self.first_result = now
        if self.first_result is not None and now - self.first_result >= rules.OBSERVE:
            return 'observed'
        if self.first_result is None and now - start > rules.STARTUP_LIMIT:
            return 'no result'
        if self.first_exit is None and any(c.rc() is not None for c in self.children.values()):
            self.first_exit = now
        if self.first_result is None and self.first_exit is not None and now - self.first_exit > rules.AFTER_EXIT:
            return 'no result'
        if self.first_result is None and self._silent(now, wanted):
            return 'no result'
        if self.children and all(c.rc() is not None for c in self.children.values()):
            time.sleep(0.5)
            return 'exited'
        return None

    def _silent(self, now, wanted):
        """True once the same nodes have been up for rules.SILENT s and none advertises a
        result topic."""
        nodes = frozenset(self.graph.nodes)
        if nodes != self.nodes_seen[0]:
            self.nodes_seen = (nodes, now)
            return False
        advertised = any(t in wanted for t, _n in self._student_topics())
        return bool(nodes) and not advertised and now - self.nodes_seen[1] > rules.SILENT

    def run(self):
        start = time.monotonic()
        not_exec = self._start()
        comp, _, _ = roles(self.isu)
        try:
            poll(lambda now: self._step(now, start, comp), 0.2)
            end = time.monotonic()
            procs = {n: {'rc': c.rc(), 'last': (c.killed_for or last_line(c.log)) if c.rc() is not None else ''}
                     for n, c in self.children.items()}
        finally:
            for c in self.children.values():
                c.stop()
        obs = {'isu': self.isu, 'scripts': sorted(self.scripts), 'not_executable': not_exec,
               'procs': procs, 'start': start, 'end': end,
               'msgs': {t: self.graph.series(t) for t in self.graph.msgs}}
        obs.update(self.graph.state())
        return obs

    def _student_topics(self):
        for n, topics in list(self.graph.pubs.items()):
            for t in topics:
                if t not in ('/rosout', '/rosout_agg'):
                    yield t, n


def observe(isu, pkg_dir, workdir):
    """The observation of the student's package at pkg_dir (the checker's entry point)."""
    return Lab1Observer(isu, rules.node_scripts(pkg_dir), workdir).run()
