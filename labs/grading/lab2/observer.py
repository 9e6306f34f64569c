"""Lab 2's observer (rospy): roslaunch the student's lab2_setup.launch, watch both turtles, the
result and the names."""
import math

import rospy
from rosgraph_msgs.msg import Log

from grading.launch import GraphWatcher, Launch, launch_failure, poll
from grading.lab2 import package, rules
from grading.lab2.criteria import LAUNCH, PACKAGE
from grading.lab2.variants import namespaces


class Motion:
    """Tracks when a turtle last moved (position by MOVE_EPS or heading by 0.05 rad)."""

    def __init__(self, eps):
        self.eps = eps
        self.anchor = None
        self.moved_at = None
        self.ever = False

    def update(self, t, x, y, th):
        if self.anchor is None:
            self.anchor = (x, y, th)
            return
        ax, ay, ath = self.anchor
        dth = abs(math.atan2(math.sin(th - ath), math.cos(th - ath)))
        if math.hypot(x - ax, y - ay) > self.eps or dth > 0.05:
            self.anchor = (x, y, th)
            self.moved_at = t
            self.ever = True


class Lab2Observer:
    """roslaunch the student's lab2_setup.launch, watch both turtles, the result and names."""

    def __init__(self, isu, pkg_dir, logdir, run_limit=None):
        self.isu = isu
        self.pkg_dir = pkg_dir
        self.logdir = logdir
        self.run_limit = run_limit or rules.RUN_LIMIT
        self.graph = GraphWatcher()
        self.walls = []
        self.poses = {k: ns + '/turtle1/pose' for k, ns in zip((1, 2), namespaces(isu))}
        self.motion = {1: Motion(rules.MOVE_EPS), 2: Motion(rules.MOVE_EPS)}
        self.seen = {1: 0, 2: 0}

    def _rosout(self, msg):
        if 'wall' in msg.msg.lower() and rules.under(msg.name, namespaces(self.isu)):
            self.walls.append('%s: %s' % (msg.name, msg.msg[:120]))

    def _subscribe(self):
        try:
            from turtlesim.msg import Pose
        except ImportError:
            raise RuntimeError('turtlesim is not built in the course workspace (no turtlesim.msg)')
        for topic in self.poses.values():
            self.graph.listen(topic, lambda m: (m.x, m.y, m.theta), Pose)
        rospy.Subscriber('/rosout_agg', Log, self._rosout, queue_size=200)

    def _step(self, now, launch, obs, progress):
        """One round: the result topics, both turtles' motion; a reason to stop, or None."""
        self.graph.poll()
        for t in list(self.graph.types):
            if t.endswith('/result_' + self.isu):
                self.graph.listen(t)
        for k, topic in self.poses.items():
            s = self.graph.series(topic)
            for (t, (x, y, th)) in s[self.seen[k]:]:
                self.motion[k].update(t, x, y, th)
            self.seen[k] = len(s)
        last = max([m.moved_at for m in self.motion.values() if m.moved_at] or [0.0])
        if launch.exited():
            if launch.child.killed_for:
                obs['launch_error'] = launch.child.killed_for
            elif not self.seen[1] and not self.seen[2]:
                obs['launch_error'] = launch_failure(launch.log)
            return 'launch_exited'
        if now - launch.start > self.run_limit:
            return 'limit'
        if not self.motion[1].ever and now - launch.start > rules.NO_MOTION_LIMIT:
            return 'no_motion'
        if self.motion[1].ever and now - last > rules.STILL_TIME:
            return 'still'
        if progress:
            progress(now - launch.start, self.motion)
        return None

    def run(self, progress=None):
        obs = {'isu': self.isu, 'remaps': package.remaps(self.pkg_dir),
               'global_literals': package.global_literals(self.pkg_dir)}
        path = package.find_launch(self.pkg_dir)
        if path is None:
            obs['launch_error'] = 'launch/%s not found in package %s' % (LAUNCH, PACKAGE)
            obs['end_reason'] = 'launch_exited'
            return obs
        self._subscribe()
        cmd = ['roslaunch', PACKAGE, LAUNCH]
        if package.declares_isu(path):
            cmd.append('isu:=%s' % self.isu)
        launch = Launch(cmd, self.logdir, self.pkg_dir)
        try:
            obs['end_reason'] = poll(lambda now: self._step(now, launch, obs, progress), 0.2)
        finally:
            launch.stop()
        start = launch.start
        obs['duration'] = (max([m.moved_at for m in self.motion.values() if m.moved_at] or [start]) - start)
        for k, topic in self.poses.items():
            obs['pose%d' % k] = [(t, x, y, th) for t, (x, y, th) in self.graph.series(topic)]
        obs['results'] = {t: self.graph.series(t) for t in self.graph.msgs if t.endswith('/result_' + self.isu)}
        obs['wall_msgs'] = list(self.walls)
        obs.update(self.graph.state())
        return obs


def observe(isu, pkg_dir, workdir):
    """The observation of the student's package at pkg_dir (the checker's entry point)."""
    return Lab2Observer(isu, pkg_dir, workdir).run()
