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
        res = [t for t in rules.result_topics(self.isu, comp) if self.graph.series(t)]
        if res and self.first_result is None:
            self.first_result = now
        if self.first_result is not None and now - self.first_result >= rules.OBSERVE:
            return 'observed'
        if self.first_result is None and now - start > rules.STARTUP_LIMIT:
            return 'no result'
        if self.children and all(c.rc() is not None for c in self.children.values()):
            time.sleep(0.5)
            return 'exited'
        return None

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
