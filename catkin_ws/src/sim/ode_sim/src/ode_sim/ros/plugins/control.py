"""libgazebo_ros_control.so: the simulator side of the ros_control bridge.

In Gazebo the plugin runs controller_manager inside gzserver. Here the controllers run in a C++
node of their own (a RobotHW talking to the simulator); this plugin is the simulator's half of
the contract documented in doc/ros_control_bridge.md:

- per robot namespace NS it publishes `NS/ode_sim/joint_states` (sensor_msgs/JointState of every
  transmission joint, once per control period, stamped with the sim time at the start of the
  period) and subscribes `NS/ode_sim/joint_commands` (sensor_msgs/JointState: the command of a
  joint in the array of its interface - position[], velocity[] or effort[]; NaN or a missing
  name keeps the previous command; header.stamp = the stamp of the state it answers);
- sets `NS/ode_sim/joints` (name, interface, lower, upper, effort, velocity, reduction per
  joint) and `NS/ode_sim/control_period` when it loads;
- applies the commands before every physics step as gazebo_ros_control's DefaultRobotHWSim does:
  effort -> joint effort; velocity -> PID on effort when NS/gazebo_ros_control/pid_gains/JOINT/p
  exists, else the joint motor at that velocity with at most the effort limit; position -> PID,
  else the joint motor servoing to it; URDF limits clamp the commands;
- eStopTopic (std_msgs/Bool): true zeroes efforts and velocities and holds positions;
- lockstep (ctx.lockstep): at each period boundary, after publishing the state of time t_k, the
  simulation waits (wall clock) for a command stamped >= t_k while a publisher is connected to
  joint_commands; after `NS/ode_sim/lockstep_timeout` (1.0 s) it warns once and steps on until
  commands flow again.

- the controller manager: when ROS is up the plugin runs gazebo_ros_control's controller
  manager (the C++ DefaultRobotHWSim + controller_manager) inside this process, as gzserver
  loads gazebo_ros_control (`<controllerNode>inprocess</controllerNode>`, an ode_sim extension,
  the default): gazebo_ros_control's libgazebo_ros_control_inprocess.so through ctypes; every
  control period the plugin hands it the joint states and takes the commands back directly,
  no topics and no lockstep waiting. `<controllerNode>true</controllerNode>` starts the same
  manager as `gazebo_ros_control_node` in NS, a child process speaking the contract's topics;
  it is stopped with the plugin (model deleted, simulator exits) and exits by itself if the
  simulator dies. `<controllerNode>false</controllerNode>` starts none: a RobotHW of one's own
  speaks the topics.

Tags as gazebo_ros_control (noetic): robotNamespace (model name), robotParam
(robot_description; the transmissions come with the model here), robotSimType (only
gazebo_ros_control/DefaultRobotHWSim), controlPeriod (physics step), eStopTopic (none);
ode_sim's controllerNode (inprocess).
"""
import math
import os
import signal
import subprocess
import threading

import rospy

from ode_sim.engine.joint_control import (  # noqa: F401 (EFFORT ... : the bridge's interfaces)
    COMMAND_INTERFACES, EFFORT, POSITION, STATE, VELOCITY, BridgeJoint, Pid, apply_commands,
    bare_interface)
from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.rosio import close

DEFAULT_SIM_TYPE = 'gazebo_ros_control/DefaultRobotHWSim'
DEFAULT_LOCKSTEP_TIMEOUT = 1.0
NODE_PACKAGE = 'gazebo_ros_control'
NODE_TYPE = 'gazebo_ros_control_node'
NODE_STOP_TIMEOUT = 5.0             # wall seconds between SIGINT and SIGKILL
INPROCESS_LIBRARY = 'libgazebo_ros_control_inprocess.so'
NODE_MODES = {'true': 'process', '1': 'process', 'process': 'process', 'inprocess': 'inprocess',
              'false': None, '0': None}


class GazeboRosControl(Plugin):
    """libgazebo_ros_control.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        self.robot_param = self.param('robotParam', 'robot_description', warn=False)
        sim_type = self.param('robotSimType', DEFAULT_SIM_TYPE, warn=False).strip()
        if sim_type != DEFAULT_SIM_TYPE:
            rospy.logwarn("gazebo_ros_control: robotSimType '%s' is not available in ode_sim; "
                          "using %s" % (sim_type, DEFAULT_SIM_TYPE))
        dt = ctx.physics.dt
        if self.has('controlPeriod'):
            period = self.param('controlPeriod', dt, float)
            if period < dt - 1e-12:
                rospy.logerr("Desired controller update period (%g s) is faster than the gazebo "
                             "simulation period (%g s)." % (period, dt))
            elif period > dt + 1e-12:
                rospy.logwarn("Desired controller update period (%g s) is slower than the gazebo "
                              "simulation period (%g s)." % (period, dt))
            self.control_period = max(period, dt)
        else:
            self.control_period = dt
        self.estop_topic = self.param('eStopTopic', '', warn=False).strip()
        mode = self.param('controllerNode', 'inprocess', warn=False).strip().lower()
        if mode not in NODE_MODES:
            raise self.error("<controllerNode> must be true (a child process), inprocess or false, "
                             "got %r" % mode)
        self.node_mode = NODE_MODES[mode]
        self.start_node = self.node_mode is not None
        self.node_proc = None
        self._inproc = None
        self.joints = self._joints_from_transmissions()
        self.by_name = {j.name: j for j in self.joints}
        self.lockstep_timeout = DEFAULT_LOCKSTEP_TIMEOUT
        self.estop = False
        self._cond = threading.Condition()
        self._cmd_stamp = -1                # newest command stamp (ns)
        self._state_stamp = 0               # stamp of the newest published state (ns)
        self._last_period = None            # sim time of the last period boundary
        self._stalled = False
        self._closing = False
        self._warned = set()
        # lockstep counters: boundaries whose command arrived in time (at once or after a wait),
        # that had to wait, that timed out
        self.synced = 0
        self.waits = 0
        self.timeouts = 0
        self._init_commands()

        from sensor_msgs.msg import JointState
        self.state_topic = self.topic('ode_sim/joint_states')
        self.command_topic = self.topic('ode_sim/joint_commands')
        self.state_pub = self.ctx.io.publisher(self.state_topic, JointState, queue_size=10)
        self.cmd_sub = self.ctx.io.subscriber(self.command_topic, JointState, self.on_command,
                                              queue_size=10, tcp_nodelay=True)
        self.estop_sub = None
        if self.estop_topic:
            from std_msgs.msg import Bool
            self.estop_sub = self.ctx.io.subscriber(self.topic(self.estop_topic), Bool,
                                                    self.on_estop)
        if self.ctx.io.live:
            self._load_ros_params()
        if not self.joints:
            rospy.logwarn("gazebo_ros_control: model '%s' has no <transmission>: nothing to "
                          "control" % model.name)
        rospy.loginfo("Starting gazebo_ros_control plugin in namespace: %s" % (self.ns or '/'))
        if self.ctx.io.live and self.node_mode == 'process':
            self._start_controller_node()
        elif self.ctx.io.live and self.node_mode == 'inprocess':
            self._start_inprocess()

    # ------------------------------------------------------------------ setup
    def _transmissions(self):
        """The model's <transmission>s; a model loaded from SDF (a saved world) has none, and
        gets them as gazebo_ros_control does: from the URDF on the parameter server (robotParam,
        looked up in the robot's namespace, then as given)."""
        if self.model.desc.transmissions or not self.ctx.io.live:
            return self.model.desc.transmissions
        from ode_sim.description.model import ModelError
        from ode_sim.description.urdf import parse_urdf
        for name in (self.topic(self.robot_param), self.robot_param):
            text = rospy.get_param(name, None)
            if isinstance(text, str) and text.strip():
                try:
                    return parse_urdf(text, 'param %s' % name, self.model.name).transmissions
                except ModelError as e:
                    rospy.logwarn('gazebo_ros_control: %s' % e)
                    return []
        return []

    def _joints_from_transmissions(self):
        out = []
        seen = set()
        for t in self._transmissions():
            if not t.joints:
                rospy.logwarn("Transmission %s has no associated joints." % t.name)
                continue
            if not t.actuators:
                rospy.logwarn("Transmission %s has no associated actuators." % t.name)
                continue
            if len(t.joints) > 1:
                rospy.logwarn("Transmission %s has more than one joint. Currently the default "
                              "robot hardware simulation interface only supports one." % t.name)
                continue
            jname, interfaces = next(iter(t.joints.items()))
            if jname not in self.model.joints:
                raise self.error('This robot has a joint named "%s" which is not in the gazebo '
                                 'model.' % jname)
            if not interfaces:
                rospy.logwarn("Joint %s of transmission %s does not specify any hardware "
                              "interface. Not adding it to the robot hardware simulation."
                              % (jname, t.name))
                continue
            if len(interfaces) > 1:
                rospy.logwarn("Joint %s of transmission %s specifies multiple hardware interfaces. "
                              "Currently the default robot hardware simulation interface only "
                              "supports one. Using the first entry" % (jname, t.name))
            iface = bare_interface(interfaces[0])
            if iface not in COMMAND_INTERFACES + (STATE,):
                raise self.error("No matching hardware interface found for '%s' while loading "
                                 "interfaces for %s" % (interfaces[0], jname))
            if jname in seen:
                continue
            seen.add(jname)
            reduction = float(next(iter(t.actuators.values()))) if t.actuators else 1.0
            out.append(BridgeJoint(self.model.joints[jname], iface, reduction))
        return out

    def _init_commands(self):
        for j in self.joints:
            j._pos = None
            j.command = j.position() if j.interface == POSITION else 0.0
            j.hold = None
            if j.pid is not None:
                j.pid.reset()

    def _load_ros_params(self):
        rospy.set_param(self.topic('ode_sim/joints'), [j.description() for j in self.joints])
        rospy.set_param(self.topic('ode_sim/control_period'), float(self.control_period))
        self.lockstep_timeout = float(rospy.get_param(self.topic('ode_sim/lockstep_timeout'),
                                                      DEFAULT_LOCKSTEP_TIMEOUT))
        for j in self.joints:
            if j.interface not in (VELOCITY, POSITION):
                continue
            ns = self.topic('gazebo_ros_control/pid_gains/' + j.name)
            gains = rospy.get_param(ns, None)
            if isinstance(gains, dict) and 'p' in gains:
                try:
                    self.set_pid_gains(j.name, **{k: float(v) for k, v in gains.items()
                                                  if k in ('p', 'i', 'd', 'i_clamp',
                                                           'i_clamp_min', 'i_clamp_max')})
                except (TypeError, ValueError):
                    raise self.error("%s: PID gains must be numbers, got %r" % (ns, gains))
            else:
                rospy.logerr("No p gain specified for pid.  Namespace: %s" % ns)

    def _start_controller_node(self):
        """gazebo_ros_control_node in NS: DefaultRobotHWSim + controller_manager."""
        from roslib.packages import find_node
        try:
            found = find_node(NODE_PACKAGE, NODE_TYPE)
        except Exception:           # package unknown to rospack
            found = []
        if not found:
            rospy.logerr("gazebo_ros_control: %s/%s not found: no controller manager runs in "
                         "namespace %s (build the workspace: catkin_make, then source "
                         "devel/setup.bash; or set <controllerNode>false</controllerNode> to "
                         "run a RobotHW of your own)" % (NODE_PACKAGE, NODE_TYPE, self.ns or '/'))
            return
        ns = '/' + self.ns.strip('/')
        cmd = [found[0], '__ns:=' + ns, '__name:=gazebo_ros_control',
               '--parent-pid', str(os.getpid())]
        if self.estop_topic:
            cmd += ['--estop-topic', self.estop_topic]
        self.node_proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL)
        rospy.loginfo("gazebo_ros_control: started the controller manager node in %s (pid %d)"
                      % (ns, self.node_proc.pid))

    def _start_inprocess(self):
        """The controller manager inside this process (see the module doc)."""
        import ctypes
        try:
            lib = ctypes.CDLL(INPROCESS_LIBRARY)
        except OSError as e:
            raise self.error("<controllerNode>inprocess</controllerNode>: cannot load %s (%s): build "
                             "the workspace and source devel/setup.bash" % (INPROCESS_LIBRARY, e))
        lib.grc_create.restype = ctypes.c_void_p
        lib.grc_create.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int]
        lib.grc_size.argtypes = [ctypes.c_void_p]
        arr = ctypes.POINTER(ctypes.c_double)
        lib.grc_update.argtypes = [ctypes.c_void_p, ctypes.c_longlong, arr, arr, arr, arr]
        lib.grc_update.restype = None
        lib.grc_destroy.argtypes = [ctypes.c_void_p]
        err = ctypes.create_string_buffer(512)
        handle = lib.grc_create(('/' + self.ns.strip('/')).encode(), self.estop_topic.encode(), err, 512)
        if not handle:
            raise self.error('the in-process controller manager failed: %s' % err.value.decode())
        n = len(self.joints)
        if lib.grc_size(handle) != n:
            lib.grc_destroy(handle)
            raise self.error('the in-process controller manager sees %d joints, the plugin %d'
                             % (lib.grc_size(handle), n))
        buf = ctypes.c_double * n
        self._inproc = (lib, handle, buf(), buf(), buf(), buf())

    def _inprocess_update(self, stamp):
        lib, handle, pos, vel, eff, cmd = self._inproc
        for k, j in enumerate(self.joints):
            pos[k] = j.position()
            vel[k] = j.joint.velocity()
            eff[k] = j.joint.effort()
        lib.grc_update(handle, stamp.to_nsec(), pos, vel, eff, cmd)
        for k, j in enumerate(self.joints):
            v = cmd[k]
            if v == v and j.interface != STATE:     # NaN: no command yet
                j.command = v

    def _stop_inprocess(self):
        inproc, self._inproc = self._inproc, None
        if inproc is not None:
            inproc[0].grc_destroy(inproc[1])

    def _stop_controller_node(self):
        proc, self.node_proc = self.node_proc, None
        if proc is None or proc.poll() is not None:
            return
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(NODE_STOP_TIMEOUT)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()

    def set_pid_gains(self, joint, p, i=0.0, d=0.0, i_clamp=0.0, i_clamp_min=None,
                      i_clamp_max=None):
        """Drive a velocity/position joint through a PID on effort (None removes it)."""
        self.by_name[joint].pid = None if p is None else Pid(p, i, d, i_clamp, i_clamp_min,
                                                             i_clamp_max)

    # ------------------------------------------------------------------ ROS callbacks
    def on_command(self, msg):
        stamp = msg.header.stamp.to_nsec()
        with self._cond:
            for k, name in enumerate(msg.name):
                j = self.by_name.get(name)
                if j is None or j.interface == STATE:
                    self._warn_once(name, "ode_sim: %s: joint '%s' takes no commands (not a "
                                    "command joint of a <transmission>); ignored"
                                    % (self.command_topic, name))
                    continue
                values = msg.effort if j.interface == EFFORT else \
                    msg.velocity if j.interface == VELOCITY else msg.position
                if k < len(values):
                    v = float(values[k])
                    if not math.isnan(v):
                        j.command = v
            if stamp == 0:
                stamp = self._state_stamp       # unstamped: answers the newest state
            self._cmd_stamp = max(self._cmd_stamp, stamp)
            self._stalled = False
            self._cond.notify_all()

    def on_estop(self, msg):
        self.estop = bool(msg.data)

    def _warn_once(self, key, text):
        if key not in self._warned:
            self._warned.add(key)
            rospy.logwarn(text)

    # ------------------------------------------------------------------ state
    def state_msg(self, stamp=None):
        from sensor_msgs.msg import JointState
        msg = JointState()
        msg.header.stamp = stamp if stamp is not None else self.ctx.now()
        msg.name = [j.name for j in self.joints]
        msg.position = [float(j.position()) for j in self.joints]
        msg.velocity = [float(j.joint.velocity()) for j in self.joints]
        msg.effort = [float(j.joint.effort()) for j in self.joints]
        return msg

    def _connected(self):
        sub = self.cmd_sub
        return sub is not None and sub.get_num_connections() > 0

    # ------------------------------------------------------------------ stepping
    def before_step(self):
        t = self.ctx.time
        last = self._last_period
        if last is None or t < last or t - last >= self.control_period - 1e-9:
            self._last_period = t
            stamp = self.ctx.now()
            if self._inproc is not None:
                # synchronous by construction: the commands of t_k come back from the call
                if self.state_pub.get_num_connections() > 0:
                    self.state_pub.publish(self.state_msg(stamp))
                self._inprocess_update(stamp)
                self.apply(self.ctx.physics.dt)
                return
            with self._cond:
                self._state_stamp = stamp.to_nsec()
            self.state_pub.publish(self.state_msg(stamp))
            if self.ctx.lockstep:
                self._wait_for(stamp)
        self.apply(self.ctx.physics.dt)

    def _wait_for(self, stamp):
        if not self._connected():
            return
        want = stamp.to_nsec()
        with self._cond:
            if self._stalled:
                return
            if self._cmd_stamp >= want:
                self.synced += 1
                return
            self.waits += 1
            deadline = self.ctx.wall.now() + self.lockstep_timeout
            while self._cmd_stamp < want and not self._closing:
                if not self._connected():   # the controller node left: nothing to wait for
                    return
                left = deadline - self.ctx.wall.now()
                if left <= 0:
                    self._stalled = True
                    self.timeouts += 1
                    rospy.logwarn("ode_sim: lockstep: no joint command for t=%.3f from %s within "
                                  "%.1f s; stepping on with the last command"
                                  % (stamp.to_sec(), self.command_topic, self.lockstep_timeout))
                    return
                self.ctx.wall.wait(self._cond, min(left, 0.2))
            if self._cmd_stamp >= want:
                self.synced += 1

    def apply(self, dt):
        """Write the commands to the joints (every physics step, as writeSim)."""
        apply_commands(self.joints, self.estop, dt)

    def reset(self):
        super().reset()
        with self._cond:
            self._init_commands()
            self._cmd_stamp = -1
            self._state_stamp = 0
            self._last_period = None
            self._stalled = False

    def shutdown(self):
        with self._cond:
            self._closing = True
            self._cond.notify_all()
        self._stop_controller_node()
        self._stop_inprocess()
        close(self.state_pub, self.cmd_sub, self.estop_sub)


PLUGINS = {
    'libgazebo_ros_control.so': GazeboRosControl,
}
