"""Lab 4's observer (rospy): roslaunch lab4.launch headless and watch /robot_description,
LaserScan and Image topics (first message each), the controller managers' list_controllers,
and /gazebo/model_states on the simulation's own clock for RUN_SIM seconds after every
controller runs."""
import math
import os
import threading
import time

import rosgraph
import rospkg
import rospy
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.msg import ModelStates
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Image, LaserScan

from grading.launch import Launch, graph_nodes, master_round, node_argv, poll
from grading.lab4 import rules
from grading.lab4.criteria import LAUNCH, PACKAGE
from grading.lab4.scene import NOT_OBJECTS, SceneError, analyse_scene, find_worlds
from grading.package import find_named


def model_dirs(pkg_dir):
    """Where model:// URIs are looked up: the simulator's models, GAZEBO_MODEL_PATH, the
    package's own models folders."""
    dirs = []
    try:
        dirs.append(os.path.join(rospkg.RosPack().get_path('ode_sim'), 'models'))
    except Exception:   # no simulator package: only the student's paths
        pass
    dirs += [d for d in os.environ.get('GAZEBO_MODEL_PATH', '').split(':') if d]
    for d, sub, _files in os.walk(pkg_dir):
        if os.path.basename(d) == 'models':
            dirs.append(d)
    return dirs


def scene(pkg_dir, argvs):
    """The world file the launch used (an existing .world/.sdf path on a node's command
    line), else the package's only/first world file."""
    used = None
    for argv in argvs:
        for a in argv:
            a = a.split(':=', 1)[-1]
            if a.endswith(('.world', '.sdf')) and os.path.isfile(a):
                used = a
                break
        if used:
            break
    if used is None:
        worlds = find_worlds(pkg_dir)
        used = worlds[0] if worlds else None
    if used is None:
        return {'error': 'no world file (.world / .sdf) in package %s' % PACKAGE,
                'error_ru': 'в пакете %s нет файла сцены (.world / .sdf)' % PACKAGE}
    with open(used, errors='replace') as f:
        return {'path': used, 'text': f.read()}


def robot_motion(states, scene_):
    """The robot (the scene's non-world model that travelled farthest), its track and the
    scene objects' first and last poses, from [(sim t, {name: pose})]."""
    if not states:
        return {'error': 'no /gazebo/model_states on sim time after the controllers started',
                'error_ru': 'нет /gazebo/model_states на времени симуляции после запуска контроллеров'}
    world_names = set()
    if scene_ and scene_.get('text'):
        try:
            world_names = set(analyse_scene(scene_['text'])['names'])
        except SceneError:
            pass
    names = set(states[0][1]) | set(states[-1][1])
    cands = sorted(n for n in names if n not in world_names and n not in NOT_OBJECTS)
    if not cands:
        return {'error': 'no robot in /gazebo/model_states (only the scene: %s)' % ', '.join(sorted(names)),
                'error_ru': 'робота нет в /gazebo/model_states (только сцена: %s)' % ', '.join(sorted(names))}

    def track(n):
        return [(t,) + p[n] for t, p in states if n in p]

    def length(tr):
        return sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(tr, tr[1:]))
    robot = max(cands, key=lambda n: length(track(n)))
    objs = {}
    for n in names:
        if n == robot or n in NOT_OBJECTS or (world_names and n not in world_names):
            continue
        ps = [p[n] for _t, p in states if n in p]
        if ps:
            objs[n] = (ps[0], ps[-1])
    return {'robot': robot, 'track': track(robot), 'objects': objs}


def list_controllers(master):
    """{name: state, type, claimed} of every controller of every controller manager; None
    while the master is busy."""
    out = {}
    try:
        srvs = [s for s, _ in master.getSystemState()[2] if s.endswith('controller_manager/list_controllers')]
    except Exception:
        return None
    for s in srvs:
        try:
            rospy.wait_for_service(s, timeout=5.0)
            resp = rospy.ServiceProxy(s, ListControllers)()
        except Exception:   # manager busy or gone: next round
            continue
        for cs in resp.controller:
            out[cs.name] = {'state': cs.state, 'type': cs.type,
                            'claimed': [(r.hardware_interface, list(r.resources)) for r in cs.claimed_resources]}
    return out


class Lab4Observer:
    """roslaunch lab4.launch headless and watch: /robot_description, LaserScan and Image topics
    (first message each), the controller managers' list_controllers, and /gazebo/model_states
    on the simulation's own clock for RUN_SIM seconds after every controller runs."""

    def __init__(self, isu, pkg_dir, logdir, startup_limit=None, run_wall_limit=None):
        self.isu = isu
        self.pkg_dir = pkg_dir
        self.logdir = logdir
        self.startup_limit = startup_limit or rules.STARTUP_LIMIT
        self.run_wall_limit = run_wall_limit or rules.RUN_WALL_LIMIT
        self.lock = threading.Lock()
        self.clock = 0.0
        self.scans, self.images = {}, {}
        self.states = []          # (sim t, {name: pose})
        self._subs = {}
        self.argvs, self.seen_nodes = [], set()
        self.ctrls = None
        self.t0 = None

    # --- callbacks ---
    def _clock(self, msg):
        with self.lock:
            self.clock = msg.clock.to_sec()

    def _scan(self, msg, topic):
        with self.lock:
            self.scans.setdefault(topic, (float(msg.range_min), float(msg.range_max)))

    def _image(self, msg, topic):
        with self.lock:
            self.images.setdefault(topic, (int(msg.width), int(msg.height)))

    def _states(self, msg):
        with self.lock:
            t = self.clock
            if self.states and t - self.states[-1][0] < 0.05:
                return
            poses = {}
            for n, p in zip(msg.name, msg.pose):
                poses[n] = (p.position.x, p.position.y, p.position.z,
                            p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w)
            self.states.append((t, poses))

    def model_dirs(self):
        return model_dirs(self.pkg_dir)

    def scene(self, argvs):
        return scene(self.pkg_dir, argvs)

    def run(self):
        obs = {'isu': self.isu, 'model_dirs': self.model_dirs()}
        obs['launch'] = self.run_launch(obs)
        return obs

    def _listen(self, master):
        try:
            types = dict(master.getTopicTypes())
        except Exception:
            return
        for topic, t in types.items():
            if topic in self._subs:
                continue
            if t == 'sensor_msgs/LaserScan':
                self._subs[topic] = rospy.Subscriber(topic, LaserScan, self._scan, callback_args=topic, queue_size=1)
            elif t == 'sensor_msgs/Image':
                self._subs[topic] = rospy.Subscriber(topic, Image, self._image, callback_args=topic,
                                                     queue_size=1, buff_size=2 ** 24)

    def _see_nodes(self, master, nodes):
        for n in sorted(nodes - self.seen_nodes):
            argv = node_argv(master, n)
            if argv:
                self.seen_nodes.add(n)
                self.argvs.append(argv)

    def _startup_round(self, master, launch, res):
        """Start-up: description, sensors, controllers (wall-clock limit, generous); a reason
        to stop, or None."""
        self._see_nodes(master, graph_nodes(master_round(master, res)))
        self._listen(master)
        c = list_controllers(master)
        if c:
            self.ctrls = c
        with self.lock:
            have_sensors = bool(self.scans) and bool(self.images)
            clock = self.clock
        running = bool(self.ctrls) and all(d['state'] == 'running' for d in self.ctrls.values())
        if running and self.t0 is None and clock > 0:
            self.t0 = clock
        if running and have_sensors and res.get('robot_description') is not None and self.t0 is not None:
            return 'ready'
        if launch.exited():
            res['error'] = 'roslaunch exited: %s' % launch.failure()
            return 'exited'
        if time.monotonic() - launch.start > self.startup_limit:
            return 'limit'
        return None

    def _motion_round(self, master, launch, res, w0):
        """Motion: RUN_SIM seconds of sim time from t0 (controllers running); a reason to stop,
        or None."""
        if time.monotonic() - w0 >= self.run_wall_limit:
            return 'limit'
        with self.lock:
            if self.clock - self.t0 >= rules.RUN_SIM:
                return 'done'
        if launch.exited():
            res['error'] = 'roslaunch exited: %s' % launch.failure(relative=False)
            return 'exited'
        c = list_controllers(master)
        if c:
            self.ctrls = c
        return None

    def _watch(self, master, launch, res):
        poll(lambda now: self._startup_round(master, launch, res), 0.5)
        res['ready_after'] = time.monotonic() - launch.start
        if self.t0 is None:
            with self.lock:
                self.t0 = self.clock if self.states else None
        if self.t0 is not None and not launch.exited():
            w0 = time.monotonic()
            poll(lambda now: self._motion_round(master, launch, res, w0), 0.5)

    def run_launch(self, obs):
        path = find_named(self.pkg_dir, LAUNCH)
        obs['scene'] = None
        if path is None:
            obs['scene'] = self.scene([])
            return {'error': 'launch/%s not found in package %s' % (LAUNCH, PACKAGE)}
        master = rosgraph.Master(rospy.get_name())
        rospy.Subscriber('/clock', Clock, self._clock, queue_size=10)
        rospy.Subscriber('/gazebo/model_states', ModelStates, self._states, queue_size=10)
        cmd = ['roslaunch', PACKAGE, LAUNCH] + rules.roslaunch_args(path, self.isu)
        env = dict(os.environ)
        env.pop('DISPLAY', None)
        env['QT_QPA_PLATFORM'] = 'offscreen'
        launch = Launch(cmd, self.logdir, self.pkg_dir, env=env)
        res = {'args': cmd[3:]}
        try:
            self._watch(master, launch, res)
        finally:
            launch.stop()
        for s in self._subs.values():
            s.unregister()
        obs['scene'] = self.scene(self.argvs)
        t0 = self.t0
        with self.lock:
            res['scans'] = dict(self.scans)
            res['images'] = dict(self.images)
            states = [s for s in self.states if t0 is not None and t0 <= s[0] <= t0 + rules.RUN_SIM]
        res['controllers'] = self.ctrls
        res['motion'] = robot_motion(states, obs['scene'])
        res['nodes'] = [' '.join(a)[:200] for a in self.argvs]
        return res


def observe(isu, pkg_dir, workdir):
    """The observation of the student's package at pkg_dir (the checker's entry point)."""
    return Lab4Observer(isu, pkg_dir, workdir).run()
