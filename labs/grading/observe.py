"""The rospy side of the checkers: start the student's nodes, watch the master and topics.

Each observer gathers a plain dict that grading.lab1 / grading.lab2 evaluate. Time stamps are
wall seconds (time.monotonic) so that a stalled node cannot stall the clock.
"""
import math
import os
import threading
import time

import rosgraph
import rospy

from grading.launch import Child, launch_failure, node_argv, plain


class Lab4Observer:
    """roslaunch lab4.launch headless and watch: /robot_description, LaserScan and Image topics
    (first message each), the controller managers' list_controllers, and /gazebo/model_states
    on the simulation's own clock for RUN_SIM seconds after every controller runs."""

    def __init__(self, isu, pkg_dir, logdir, startup_limit=None, run_wall_limit=None):
        from grading import lab4
        self.lab4 = lab4
        self.isu = isu
        self.pkg_dir = pkg_dir
        self.logdir = logdir
        self.startup_limit = startup_limit or lab4.STARTUP_LIMIT
        self.run_wall_limit = run_wall_limit or lab4.RUN_WALL_LIMIT
        self.lock = threading.Lock()
        self.clock = 0.0
        self.scans, self.images = {}, {}
        self.states = []          # (sim t, {name: pose})
        self._subs = {}

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
        dirs = []
        try:
            import rospkg
            dirs.append(os.path.join(rospkg.RosPack().get_path('ode_sim'), 'models'))
        except Exception:   # no simulator package: only the student's paths
            pass
        dirs += [d for d in os.environ.get('GAZEBO_MODEL_PATH', '').split(':') if d]
        for d, sub, _files in os.walk(self.pkg_dir):
            if os.path.basename(d) == 'models':
                dirs.append(d)
        return dirs

    def scene(self, argvs):
        """The world file the launch used (an existing .world/.sdf path on a node's command
        line), else the package's only/first world file."""
        lab4 = self.lab4
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
            worlds = lab4.find_worlds(self.pkg_dir)
            used = worlds[0] if worlds else None
        if used is None:
            return {'error': 'no world file (.world / .sdf) in package %s' % lab4.PACKAGE,
                    'error_ru': 'в пакете %s нет файла сцены (.world / .sdf)' % lab4.PACKAGE}
        with open(used, errors='replace') as f:
            return {'path': used, 'text': f.read()}

    def run(self):
        obs = {'isu': self.isu, 'model_dirs': self.model_dirs()}
        obs['launch'] = self.run_launch(obs)
        return obs

    def _controllers(self, master):
        from controller_manager_msgs.srv import ListControllers
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

    def _listen(self, master):
        from sensor_msgs.msg import Image, LaserScan
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

    def run_launch(self, obs):
        lab4 = self.lab4
        from gazebo_msgs.msg import ModelStates
        from rosgraph_msgs.msg import Clock
        launch = lab4.find_launch(self.pkg_dir)
        obs['scene'] = None
        if launch is None:
            obs['scene'] = self.scene([])
            return {'error': 'launch/%s not found in package %s' % (lab4.LAUNCH, lab4.PACKAGE)}
        master = rosgraph.Master(rospy.get_name())
        rospy.Subscriber('/clock', Clock, self._clock, queue_size=10)
        rospy.Subscriber('/gazebo/model_states', ModelStates, self._states, queue_size=10)
        cmd = ['roslaunch', lab4.PACKAGE, lab4.LAUNCH] + lab4.launch_args(launch, self.isu)
        log = os.path.join(self.logdir, 'roslaunch.log')
        env = dict(os.environ)
        env.pop('DISPLAY', None)
        env['QT_QPA_PLATFORM'] = 'offscreen'
        start = time.monotonic()
        child = Child(cmd, log, env=env)
        res = {'args': cmd[3:]}
        argvs, seen_nodes = [], set()
        ctrls = None
        t0 = None
        try:
            # start-up: description, sensors, controllers (wall-clock limit, generous)
            while not rospy.is_shutdown():
                try:
                    if res.get('robot_description') is None and master.hasParam('/robot_description'):
                        v = master.getParam('/robot_description')
                        res['robot_description'] = v if isinstance(v, str) else str(v)
                    nodes = set()
                    for table in master.getSystemState():
                        for _topic, ns in table:
                            nodes.update(ns)
                except Exception:   # master busy or not up yet
                    nodes = set()
                for n in sorted(nodes - seen_nodes):
                    argv = node_argv(master, n)
                    if argv:
                        seen_nodes.add(n)
                        argvs.append(argv)
                self._listen(master)
                c = self._controllers(master)
                if c:
                    ctrls = c
                with self.lock:
                    have_sensors = bool(self.scans) and bool(self.images)
                    clock = self.clock
                running = bool(ctrls) and all(d['state'] == 'running' for d in ctrls.values())
                if running and t0 is None and clock > 0:
                    t0 = clock
                if running and have_sensors and res.get('robot_description') is not None and t0 is not None:
                    break
                if child.rc() is not None:
                    res['error'] = 'roslaunch exited: %s' % plain(child.killed_for or launch_failure(log)).replace(self.pkg_dir.rstrip('/') + '/', '')
                    break
                if time.monotonic() - start > self.startup_limit:
                    break
                time.sleep(0.5)
            res['ready_after'] = time.monotonic() - start
            # motion: RUN_SIM seconds of sim time from t0 (controllers running)
            if t0 is None:
                with self.lock:
                    t0 = self.clock if self.states else None
            if t0 is not None and child.rc() is None:
                w0 = time.monotonic()
                while not rospy.is_shutdown() and time.monotonic() - w0 < self.run_wall_limit:
                    with self.lock:
                        if self.clock - t0 >= lab4.RUN_SIM:
                            break
                    if child.rc() is not None:
                        res['error'] = 'roslaunch exited: %s' % plain(child.killed_for or launch_failure(log))
                        break
                    c = self._controllers(master)
                    if c:
                        ctrls = c
                    time.sleep(0.5)
        finally:
            child.stop()
        for s in self._subs.values():
            s.unregister()
        obs['scene'] = self.scene(argvs)
        with self.lock:
            res['scans'] = dict(self.scans)
            res['images'] = dict(self.images)
            states = [s for s in self.states if t0 is not None and t0 <= s[0] <= t0 + lab4.RUN_SIM]
        res['controllers'] = ctrls
        res['motion'] = self._motion(states, obs['scene'])
        res['nodes'] = [' '.join(a)[:200] for a in argvs]
        return res

    def _motion(self, states, scene):
        lab4 = self.lab4
        if not states:
            return {'error': 'no /gazebo/model_states on sim time after the controllers started',
                    'error_ru': 'нет /gazebo/model_states на времени симуляции после запуска контроллеров'}
        world_names = set()
        if scene and scene.get('text'):
            try:
                world_names = set(lab4.analyse_scene(scene['text'])['names'])
            except lab4.SceneError:
                pass
        names = set(states[0][1]) | set(states[-1][1])
        cands = sorted(n for n in names if n not in world_names and n not in lab4.NOT_OBJECTS)
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
            if n == robot or n in lab4.NOT_OBJECTS or (world_names and n not in world_names):
                continue
            ps = [p[n] for _t, p in states if n in p]
            if ps:
                objs[n] = (ps[0], ps[-1])
        return {'robot': robot, 'track': track(robot), 'objects': objs}
