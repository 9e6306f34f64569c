"""What a window needs from the simulator beyond gazebo_ros's /gazebo/* API (what gzclient gets
from gzserver over Gazebo transport), as ode_sim_msgs types:

- /gazebo/get_world_sdf (ode_sim_msgs/GetWorldSDF): the current world as File -> Save World As
  writes it (description/save_world.py);
- /gazebo/step_world (ode_sim_msgs/StepWorld): exactly N physics steps of a paused world;
- /gazebo/world_stats (ode_sim_msgs/WorldStatistics, 5 Hz of wall time): sim, real and pause
  time, iterations, paused, real-time factor, step size (the window's bottom bar);
- /gazebo/pose_info (ode_sim_msgs/PoseInfo, at most 60 Hz of wall time while subscribed, running
  or paused): every model's and link's pose, read on its own thread under the node's lock, so a
  window costs the simulation nothing per step (gazebo_msgs' model_states / link_states are
  published every step and make the node step one step at a time).

Also spawn_light(): /gazebo/spawn_sdf_model with a <light> (GazeboApi.spawn_sdf calls it).
"""
import threading
import time

import rospy
from ode_sim_msgs import msg as om
from ode_sim_msgs import srv as osrv

from ode_sim.description import save_world, sdf
from ode_sim.description.model import ModelError
from ode_sim.ros.convert import pose_from_msg, pose_msg
from ode_sim.ros.gazebo_lights import attenuation_of
from ode_sim.ros.gazebo_state import SPAWN_REFERENCE_NOT_FOUND

STATS_PERIOD = 0.2          # wall seconds between /gazebo/world_stats messages
POSE_PERIOD = 1.0 / 60      # wall seconds between /gazebo/pose_info messages at most
RTF_WINDOW = 1.0            # wall seconds the real-time factor is measured over


class RealTimeFactor:
    """Sim seconds per wall second over the last `window` wall seconds (as Gazebo's statistics,
    from samples); 0 while paused or before two samples. Injectable times: no wall clock."""

    def __init__(self, window=RTF_WINDOW):
        self.window = window
        self.samples = []           # (wall, sim)

    def add(self, wall, sim):
        if self.samples and sim < self.samples[-1][1]:
            self.samples = []       # reset_simulation: start over
        self.samples.append((wall, sim))
        while len(self.samples) > 2 and wall - self.samples[1][0] >= self.window:
            self.samples.pop(0)

    def value(self):
        if len(self.samples) < 2:
            return 0.0
        (w0, s0), (w1, s1) = self.samples[0], self.samples[-1]
        return (s1 - s0) / (w1 - w0) if w1 > w0 else 0.0


class WorldControl:
    """The services and topic above on a SimNode (and its GazeboApi, for the lights'
    attenuation, when there is one)."""

    def __init__(self, node, api=None, ns='/gazebo', stats=True):
        self.node = node
        self.api = api
        n = ns.rstrip('/')
        self.start_wall = time.monotonic()
        self.pause_time = 0.0
        self.rtf = RealTimeFactor()
        self.services = [
            rospy.Service(n + '/get_world_sdf', osrv.GetWorldSDF, self.get_world_sdf),
            rospy.Service(n + '/step_world', osrv.StepWorld, self.step_world),
        ]
        self.stats_pub = rospy.Publisher(n + '/world_stats', om.WorldStatistics, queue_size=1)
        self.pose_pub = rospy.Publisher(n + '/pose_info', om.PoseInfo, queue_size=1)
        self._threads = []
        if stats:
            for target, name in ((self._stats_loop, 'world_stats'),
                                 (self._pose_loop, 'pose_info')):
                t = threading.Thread(target=target, name=name, daemon=True)
                t.start()
                self._threads.append(t)

    # ----------------------------------------------------------------- Save World
    def world_text(self):
        """The current world's SDF (under the node's lock)."""
        node = self.node
        with node.lock:
            pw = node.physics
            return save_world.world_sdf(
                node.world, list(pw.models.values()), gravity=pw.gravity, sim_time=pw.time,
                real_time=time.monotonic() - self.start_wall, iterations=pw.steps,
                attenuations=getattr(self.api, '_attenuation', None))

    def get_world_sdf(self, _req):
        try:
            text = self.world_text()
        except Exception as e:          # a model the writer cannot express: say which
            rospy.logerr('ode_sim: get_world_sdf: %s: %s' % (type(e).__name__, e))
            return osrv.GetWorldSDFResponse('', False, 'GetWorldSDF: %s' % e)
        return osrv.GetWorldSDFResponse(text, True, 'GetWorldSDF: got the world')

    # ----------------------------------------------------------------- stepping
    def step(self, steps):
        """Exactly `steps` physics steps (the node is paused): in the node's step groups, so
        plugins run at the very steps they would when running. (ok, message)."""
        node = self.node
        if not node.paused:
            return False, 'StepWorld: the world is running; pause it first (/gazebo/pause_physics)'
        target = node.physics.steps + int(steps)
        while node.physics.steps < target:
            if not node.paused:
                return False, ('StepWorld: the world was unpaused after %d of %d steps'
                               % (int(steps) - (target - node.physics.steps), steps))
            node.step_once(max(1, min(node.group_size(), target - node.physics.steps)))
        node.publish_clock(force=True)
        return True, 'StepWorld: %d steps done' % steps

    def step_world(self, req):
        ok, message = self.step(req.steps)
        pw = self.node.physics
        return osrv.StepWorldResponse(ok, message, pw.time, pw.steps)

    # ----------------------------------------------------------------- statistics
    def stats(self, wall=None):
        wall = time.monotonic() if wall is None else wall
        pw = self.node.physics
        self.rtf.add(wall, pw.time)
        m = om.WorldStatistics()
        m.sim_time = rospy.Time.from_sec(pw.time)
        m.real_time = rospy.Time.from_sec(max(0.0, wall - self.start_wall))
        m.pause_time = rospy.Time.from_sec(self.pause_time)
        m.iterations = pw.steps
        m.paused = bool(self.node.paused)
        m.real_time_factor = 0.0 if m.paused else self.rtf.value()
        m.max_step_size = float(pw.dt)
        return m

    # ----------------------------------------------------------------- poses
    def pose_info(self):
        """PoseInfo of the world now (under the node's lock)."""
        m = om.PoseInfo()
        with self.node.lock:
            pw = self.node.physics
            m.sim_time = rospy.Time.from_sec(pw.time)
            m.iterations = pw.steps
            for name, model in pw.models.items():
                m.model_name.append(name)
                m.model_pose.append(pose_msg(model.pose()))
                for lname, link in model.links.items():
                    m.link_name.append('%s::%s' % (name, lname))
                    m.link_pose.append(pose_msg(link.pose()))
        return m

    def _pose_loop(self):
        while not rospy.is_shutdown():
            if self.pose_pub.get_num_connections() == 0:
                time.sleep(STATS_PERIOD / 2)     # nobody listens: look again 10 times a second
                continue
            time.sleep(POSE_PERIOD)
            try:
                self.pose_pub.publish(self.pose_info())
            except rospy.ROSException:          # shutting down
                return

    def _stats_loop(self):
        last = time.monotonic()
        while not rospy.is_shutdown():
            time.sleep(STATS_PERIOD)
            now = time.monotonic()
            if self.node.paused:
                self.pause_time += now - last
            last = now
            try:
                self.stats_pub.publish(self.stats(now))
            except rospy.ROSException:          # shutting down
                return


def spawn_light(api, req):
    """/gazebo/spawn_sdf_model of a <light> (or an <include> of one): the light is added to the
    world as gazebo_ros' spawnSDFModel does, named model_name, its pose composed with
    initial_pose (in reference_frame). None when the
    SDF describes a model (GazeboApi then spawns it)."""
    from gazebo_msgs.srv import SpawnModelResponse
    source = 'spawn_sdf_model(%s)' % req.model_name
    try:
        light = sdf.parse_sdf_light(req.model_xml, source, name=req.model_name)
    except ModelError as e:
        return SpawnModelResponse(False, 'SpawnModel: Failure - %s' % e)
    if light is None:
        return None
    node = api.node
    with node.lock:
        if any(lt.name == light.name for lt in node.world.lights):
            return SpawnModelResponse(False, 'SpawnModel: Failure - entity already exists.')
        ref, error = api._reference(req.reference_frame, SPAWN_REFERENCE_NOT_FOUND % req.reference_frame)
        if error:
            return SpawnModelResponse(False, error)
        light.pose = ref[0] * pose_from_msg(req.initial_pose) * light.pose
        node.world.lights.append(light)
        api._attenuation[light.name] = attenuation_of(light.element)
        api._lights_changed()
    return SpawnModelResponse(True, 'SpawnModel: Successfully spawned entity')
