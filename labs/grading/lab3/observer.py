"""Lab 3's observer (rospy): expand the model with xacro, check_urdf it, then roslaunch
lab3_setup.launch and watch /robot_description, the nodes (by their executables), the RViz
config and /tf."""
import os
import threading
import time

import course_runtime
import rosgraph
import rospy
from course_runtime import SOFTWARE_GL, Xvfb
from tf2_msgs.msg import TFMessage

from grading.launch import (Launch, error_line, graph_nodes, launch_failure, master_round, node_process, plain, poll,
                            process_argv)
from grading.lab3 import rules
from grading.lab3.criteria import LAUNCH, MODEL, PACKAGE
from grading.lab3.model import xacro_args
from grading.lab3.rviz import node_kind, rviz_config_arg, rviz_displays
from grading.package import find_file, find_named, launch_args, variant_args
from grading.urdf import ModelError, parse_urdf


class Lab3Observer:
    """Expand the model with xacro, check_urdf it, then roslaunch lab3_setup.launch and watch
    /robot_description, the nodes (by their executables), the RViz config and /tf."""

    def __init__(self, isu, pkg_dir, logdir, launch_limit=None):
        self.isu = isu
        self.pkg_dir = pkg_dir
        self.logdir = logdir
        self.launch_limit = launch_limit or rules.LAUNCH_LIMIT
        self.frames = set()
        self.lock = threading.Lock()
        self.argv_seen = {}
        self.rviz_up = False
        self.rviz_pid = None
        self._seen = None               # (nodes, frames) at the last look
        self._changed = None            # when they last changed

    def _step(self, cmd, name):
        """(rc or None on timeout, combined output) of a short command."""
        log = os.path.join(self.logdir, name + '.log')
        rc, timed_out = course_runtime.run(cmd, rules.STEP_TIMEOUT, cwd=self.logdir, log=log)
        with open(log, errors='replace') as f:
            return (None if timed_out else rc), f.read()

    def static(self, obs):
        path = find_file(self.pkg_dir, MODEL)
        obs['model_found'] = bool(path)
        if not path:
            return
        args = variant_args(xacro_args(path), self.isu)
        obs['xacro_args'] = args
        out_urdf = os.path.join(self.logdir, 'model.urdf')
        rc, text = self._step(['bash', '-c', 'rosrun xacro xacro "$@" > "%s"' % out_urdf, 'xacro', path] + args,
                              'xacro')
        if rc is None:
            obs['xacro_error'] = 'did not finish within %d s' % rules.STEP_TIMEOUT
            return
        if rc != 0:
            line = error_line(text, ('error', 'Error', 'XacroException', 'Undefined', 'not well-formed', 'Exception'))
            line = line[len('xacro: '):] if line.startswith('xacro: ') else line
            obs['xacro_error'] = line.replace(self.pkg_dir.rstrip('/') + '/', '')
            return
        with open(out_urdf, errors='replace') as f:
            obs['urdf'] = f.read()
        rc, text = self._step(['check_urdf', out_urdf], 'check_urdf')
        if rc is None:
            obs['check_urdf_error'] = 'did not finish within %d s' % rules.STEP_TIMEOUT
        elif rc != 0:
            obs['check_urdf_error'] = error_line(text, ('Error', 'error', 'ERROR'))

    def _tf(self, msg):
        with self.lock:
            for t in msg.transforms:
                self.frames.add(t.child_frame_id.lstrip('/'))
                self.frames.add(t.header.frame_id.lstrip('/'))

    def run(self):
        obs = {'isu': self.isu}
        self.static(obs)
        obs['launch'] = self.run_launch(obs)
        return obs

    def _screen(self, env):
        """The grading's own X screen when there is no display (None otherwise)."""
        if env.get('DISPLAY'):
            return None
        xvfb = Xvfb(1600, 1000)
        xvfb.start()
        env['DISPLAY'] = xvfb.display
        # the grading's own screen, that nobody looks at: drawn by Mesa's softpipe (no
        # JIT), so that llvmpipe's rare crash inside LLVM 15 cannot end a student's RViz
        for k, v in SOFTWARE_GL.items():
            env.setdefault(k, v)
        return xvfb

    def _see_nodes(self, master, nodes, res):
        """Record the command line and kind of every node not seen yet."""
        for n in sorted(nodes):
            if n in self.argv_seen or n == rospy.get_name() or n == '/rosout':
                continue
            pid, argv = node_process(master, n)
            if argv:
                self.argv_seen[n] = argv
                kind = node_kind(argv)
                if kind:
                    res['kinds'].setdefault(kind, []).append(n)
                    if kind == 'rviz':
                        res['rviz']['argv'] = argv
                        self.rviz_pid = pid

    def _round(self, now, master, launch, res, want_links):
        """One look at the graph; a reason to stop, or None."""
        state = master_round(master, res)
        nodes = graph_nodes(state)
        tf_subs = set(ns for topic, ns_list in (state[1] if state else ()) if topic == '/tf' for ns in ns_list)
        self._see_nodes(master, nodes, res)
        with self.lock:
            frames = set(self.frames)
        # RViz is up once its display manager listens to /tf (the render window exists)
        self.rviz_up = any(n in tf_subs for n in res['kinds'].get('rviz', []))
        ready = (res.get('robot_description') is not None and len(res['kinds']) == 3
                 and self.rviz_up and want_links is not None and want_links <= frames)
        if ready:
            res['ready_after'] = now - launch.start
            time.sleep(rules.RVIZ_SETTLE)   # RViz must still be running afterwards
            return 'ready'
        if launch.exited():
            res['error'] = 'roslaunch exited: %s' % launch.failure()
            return 'exited'
        if now - launch.start > self.launch_limit:
            return 'limit'
        return self._settled(now, nodes, frames, res)

    def _settled(self, now, nodes, frames, res):
        """'settled' once RViz is up and the description set, and neither the nodes nor the
        TF frames have changed for rules.SETTLED s: a missing piece (a node that is not in the
        launch file, a link nobody publishes) will not come, so there is no need to wait out
        the launch limit; None otherwise."""
        seen = (frozenset(nodes), frozenset(frames))
        if seen != self._seen:
            self._seen, self._changed = seen, now
            return None
        if self.rviz_up and res.get('robot_description') is not None and now - self._changed > rules.SETTLED:
            return 'settled'
        return None

    def _rviz_still_up(self, launch, res):
        """RViz still running after the settle time: judged by its process (the same PID, the
        same command line), not by its XML-RPC answer, which a loaded machine can delay past
        the request."""
        if 'rviz' in res['kinds'] and process_argv(self.rviz_pid) != res['rviz']['argv']:
            res['kinds'].pop('rviz')
            res['error'] = res.get('error') or 'rviz exited: %s' % plain(launch_failure(launch.log))
        elif 'rviz' in res['kinds'] and not res.get('ready_after') and not self.rviz_up:
            res['rviz']['not_up'] = True

    def _rviz_config(self, rv):
        """The displays and fixed frame of the config RViz was started with."""
        argv = rv.get('argv')
        if not argv:
            return
        cfg = rviz_config_arg(argv)
        rv['config'] = cfg
        if cfg:
            try:
                with open(cfg, errors='replace') as f:
                    classes, frame = rviz_displays(f.read())
                rv.update(classes=classes, fixed_frame=frame)
            except OSError as e:
                rv['config_error'] = 'cannot read: %s' % e.strerror
            except ModelError as e:
                rv['config_error'] = str(e)

    def run_launch(self, obs):
        path = find_named(self.pkg_dir, LAUNCH)
        if path is None:
            return {'error': 'launch/%s not found in package %s' % (LAUNCH, PACKAGE)}
        want_links = None
        if obs.get('urdf'):
            try:
                want_links = set(parse_urdf(obs['urdf'])['links'])
            except ModelError:
                want_links = None
        rospy.Subscriber('/tf', TFMessage, self._tf, queue_size=200)
        rospy.Subscriber('/tf_static', TFMessage, self._tf, queue_size=50)
        master = rosgraph.Master(rospy.get_name())
        env = dict(os.environ)
        xvfb = self._screen(env)
        env.pop('QT_QPA_PLATFORM', None)
        cmd = ['roslaunch', PACKAGE, LAUNCH] + variant_args(launch_args(path), self.isu)
        launch = Launch(cmd, self.logdir, self.pkg_dir, env=env)
        res = {'kinds': {}, 'rviz': {}}
        try:
            poll(lambda now: self._round(now, master, launch, res, want_links), 0.3)
            self._rviz_still_up(launch, res)
        finally:
            launch.stop()
            if xvfb is not None:
                xvfb.stop()
        with self.lock:
            res['tf_frames'] = sorted(self.frames)
        self._rviz_config(res['rviz'])
        res['nodes'] = {n: ' '.join(a)[:200] for n, a in self.argv_seen.items()}
        return res


def observe(isu, pkg_dir, workdir):
    """The observation of the student's package at pkg_dir (the checker's entry point)."""
    return Lab3Observer(isu, pkg_dir, workdir).run()
