"""MoveBase: the move_base action server. The state machine (PLANNING, CONTROLLING,
CLEARING), oscillation detection and the recovery sequence are in ``core``; this node reads
the parameters, loads the planners and recovery behaviours, runs the planner thread and the
control loop and talks ROS (action server, topics, services, tf)."""
import sys
import threading

import actionlib
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped, Twist
from move_base_msgs.msg import (MoveBaseAction, MoveBaseFeedback,
                                MoveBaseResult, RecoveryStatus)
from nav_msgs.srv import GetPlan, GetPlanResponse
from std_srvs.srv import Empty, EmptyResponse

import nav_core
from costmap_2d.costmap_2d_ros import Costmap2DROS
from costmap_2d.params import CostmapParamError

from . import conversions as conv
from . import core


class MoveBase:
    def __init__(self):
        P = lambda name, default: rospy.get_param('~' + name, default)  # noqa: E731
        self.global_planner_name = str(P('base_global_planner', 'navfn/NavfnROS'))
        self.local_planner_name = str(P('base_local_planner',
                                        'base_local_planner/TrajectoryPlannerROS'))
        self.robot_base_frame = str(P('global_costmap/robot_base_frame', 'base_link'))
        self.global_frame = str(P('global_costmap/global_frame', 'map'))
        self.config = core.Config(
            planner_frequency=float(P('planner_frequency', 0.0)),
            planner_patience=float(P('planner_patience', 5.0)),
            controller_patience=float(P('controller_patience', 15.0)),
            max_planning_retries=int(P('max_planning_retries', -1)),
            oscillation_timeout=float(P('oscillation_timeout', 0.0)),
            oscillation_distance=float(P('oscillation_distance', 0.5)),
            recovery_behavior_enabled=bool(P('recovery_behavior_enabled', True)))
        self.controller_frequency = float(P('controller_frequency', 20.0))
        self.conservative_reset_dist = float(P('conservative_reset_dist', 3.0))
        self.clearing_rotation_allowed = bool(P('clearing_rotation_allowed', True))
        self.shutdown_costmaps = bool(P('shutdown_costmaps', False))
        self.make_plan_clear_costmap = bool(P('make_plan_clear_costmap', True))
        self.make_plan_add_unreachable_goal = bool(P('make_plan_add_unreachable_goal', True))
        self.circumscribed_radius = float(P('local_costmap/circumscribed_radius', 0.46))
        if self.controller_frequency <= 0:
            rospy.logwarn('~controller_frequency must be positive, got %s; using 20.0'
                          % self.controller_frequency)
            self.controller_frequency = 20.0

        self.tf_buffer = tf2_ros.Buffer(rospy.Duration(10.0))
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)

        self.vel_pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)
        self.current_goal_pub = rospy.Publisher('~current_goal', PoseStamped, queue_size=0)
        self.recovery_status_pub = rospy.Publisher('~recovery_status', RecoveryStatus,
                                                   queue_size=1)
        self.action_goal_pub = rospy.Publisher('move_base/goal', conv.MoveBaseActionGoal,
                                               queue_size=1)

        # the planners first: an unknown name is fatal, as in the original
        global_cls = self._load('global', self.global_planner_name)
        local_cls = self._load('local', self.local_planner_name)
        try:
            self.planner_costmap = Costmap2DROS('global_costmap', self.tf_buffer)
            self.controller_costmap = Costmap2DROS('local_costmap', self.tf_buffer)
        except CostmapParamError as e:
            rospy.logfatal(str(e))
            sys.exit(1)
        self.planner = global_cls()
        self.planner.initialize(nav_core.resolve_name('global', self.global_planner_name)
                                .split('/')[-1], self.planner_costmap)
        self.tc = local_cls()
        self.tc.initialize(nav_core.resolve_name('local', self.local_planner_name)
                           .split('/')[-1], self.tf_buffer, self.controller_costmap)
        self.recovery_behaviors = self._load_recovery_behaviors()

        self._cycle_pose = None     # the robot's pose in the current control cycle
        self.core = core.MoveBaseCore(self.config, self.tc, self.recovery_behaviors,
                                      _RosOutputs(self), lambda: rospy.Time.now().to_sec())
        self.cycle_times = []   # (sim start, wall duration) of control cycles, for the bench

        self.plan_thread = threading.Thread(target=self._plan_thread, name='move_base_plan',
                                            daemon=True)
        self.plan_thread.start()

        self.server = actionlib.SimpleActionServer('move_base', MoveBaseAction,
                                                   execute_cb=self._execute_cb, auto_start=False)
        self.goal_sub = rospy.Subscriber('move_base_simple/goal', PoseStamped, self._goal_cb)
        self.make_plan_srv = rospy.Service('~make_plan', GetPlan, self._make_plan_service)
        self.clear_srv = rospy.Service('~clear_costmaps', Empty, self._clear_costmaps_service)
        self.server.start()
        rospy.loginfo('move_base: %s + %s, controller_frequency %.1f Hz'
                      % (self.global_planner_name, self.local_planner_name,
                         self.controller_frequency))

    # ---- set-up --------------------------------------------------------------------------
    def _load(self, kind, name):
        try:
            return nav_core.load_class(kind, name)
        except nav_core.PluginError as e:
            rospy.logfatal('Failed to create the %s planner, are you sure it is properly '
                           'registered and that the containing library is built? Exception: %s'
                           % (name, e))
            rospy.signal_shutdown('unknown planner %s' % name)
            sys.exit(1)

    def _load_recovery_behaviors(self):
        behaviors = []
        spec = rospy.get_param('~recovery_behaviors', None)
        if spec is not None:
            ok = isinstance(spec, list)
            names = set()
            for i, b in enumerate(spec if ok else []):
                if not isinstance(b, dict) or 'name' not in b or 'type' not in b:
                    rospy.logerr('Recovery behaviors must be specified as maps, but they are '
                                 'XmlRpcType %r. We\'ll use the default recovery behaviors '
                                 'instead.' % (b,))
                    ok = False
                    break
                if b['name'] in names:
                    rospy.logerr('A recovery behavior with the name %s already exists, this is '
                                 'not allowed. Using the default recovery behaviors instead.'
                                 % b['name'])
                    ok = False
                    break
                names.add(b['name'])
                try:
                    cls = nav_core.load_class('recovery', b['type'])
                except nav_core.PluginError as e:
                    rospy.logerr('Failed to create the %s recovery behavior (%s), are you sure '
                                 'it is properly registered? Exception: %s. Using the default '
                                 'recovery behaviors instead.' % (b['name'], b['type'], e))
                    ok = False
                    break
                behaviors.append((b['name'], b['type'], cls))
            if ok and behaviors:
                return [self._make_behavior(n, t, c) for n, t, c in behaviors]
            if not ok:
                behaviors = []
        # the defaults (loadDefaultRecoveryBehaviors)
        rospy.set_param('~conservative_reset/reset_distance', self.conservative_reset_dist)
        rospy.set_param('~aggressive_reset/reset_distance', self.circumscribed_radius * 4)
        clear = 'clear_costmap_recovery/ClearCostmapRecovery'
        rotate = 'rotate_recovery/RotateRecovery'
        seq = [('conservative_reset', clear)]
        if self.clearing_rotation_allowed:
            seq.append(('rotate_recovery', rotate))
        seq.append(('aggressive_reset', clear))
        if self.clearing_rotation_allowed:
            seq.append(('rotate_recovery', rotate))
        return [self._make_behavior(n, t, nav_core.load_class('recovery', t)) for n, t in seq]

    def _make_behavior(self, name, type_, cls):
        b = cls()
        b.initialize(name, self.tf_buffer, self.planner_costmap, self.controller_costmap)
        b.behavior_name = name
        b.behavior_type = type_
        return b

    # ---- helpers -------------------------------------------------------------------------
    def publish_zero_velocity(self):
        self.vel_pub.publish(Twist())

    def _goal_cb(self, goal):
        rospy.logdebug('In ROS goal callback, wrapping the PoseStamped in the action message '
                       'and re-sending to the server.')
        self.action_goal_pub.publish(conv.action_goal(goal))

    def _goal_to_global_frame(self, goal):
        frame = goal.header.frame_id.lstrip('/') or self.global_frame
        if frame == self.planner_costmap.global_frame:
            return goal
        try:
            t = self.tf_buffer.lookup_transform(self.planner_costmap.global_frame, frame,
                                                rospy.Time(0), rospy.Duration(0.5))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException) as e:
            rospy.logwarn('Failed to transform the goal pose from %s into the %s frame: %s'
                          % (frame, self.planner_costmap.global_frame, e))
            return goal
        return conv.transform_pose(goal, t, self.planner_costmap.global_frame)

    def _robot_pose_stamped(self, costmap):
        pose = costmap.get_robot_pose()
        if pose is None:
            return None
        return conv.pose_stamped(costmap.global_frame, *pose)

    def make_plan(self, goal, tolerance=None):
        start = self._robot_pose_stamped(self.planner_costmap)
        if start is None:
            rospy.logwarn('Unable to get starting pose of robot, unable to create global plan')
            return []
        if tolerance is None:
            return self.planner.make_plan(start, goal)
        return self.planner.make_plan(start, goal, tolerance)

    def reset_state(self):
        self.core.reset()

    # ---- the planner thread ----------------------------------------------------------------
    def _plan_thread(self):
        mb = self.core
        while not rospy.is_shutdown():
            with mb.lock:
                while not mb.run_planner and not rospy.is_shutdown():
                    mb.planner_cond.wait(0.2)
                if rospy.is_shutdown():
                    return
                goal = mb.planner_goal
                start_time = rospy.Time.now()
            plan = self.make_plan(goal) if goal is not None else []
            mb.plan_done(plan)
            if self.config.planner_frequency > 0:
                end = start_time + rospy.Duration(1.0 / self.config.planner_frequency)
                while rospy.Time.now() < end and not rospy.is_shutdown():
                    rospy.sleep(0.02)
            elif not plan:
                # retry promptly, but let the controller loop run
                rospy.sleep(0.05)

    # ---- the action ------------------------------------------------------------------------
    def _start_goal(self, goal):
        goal = self._goal_to_global_frame(goal)
        self.core.start_goal(goal)
        self.current_goal_pub.publish(goal)
        return goal

    def _execute_cb(self, move_base_goal):
        if not conv.quaternion_valid(move_base_goal.target_pose.pose.orientation):
            self.server.set_aborted(MoveBaseResult(), 'Aborting on goal because it was sent '
                                    'with an invalid quaternion')
            return
        self.publish_zero_velocity()
        goal = self._start_goal(move_base_goal.target_pose)
        if self.shutdown_costmaps:
            self.planner_costmap.start()
            self.controller_costmap.start()
        period = rospy.Duration(1.0 / self.controller_frequency)
        next_cycle = rospy.Time.now()
        while not rospy.is_shutdown():
            if self.server.is_preempt_requested():
                if self.server.is_new_goal_available():
                    new_goal = self.server.accept_new_goal()
                    if not conv.quaternion_valid(new_goal.target_pose.pose.orientation):
                        self.server.set_aborted(MoveBaseResult(), 'Aborting on goal because it '
                                                'was sent with an invalid quaternion')
                        return
                    goal = self._start_goal(new_goal.target_pose)
                else:
                    self.reset_state()
                    rospy.logdebug('Move base preempting the current goal')
                    self.server.set_preempted()
                    return
            wall0 = rospy.get_time()
            sim0 = rospy.Time.now()
            wall_start = _wall()
            done = self._execute_cycle(goal)
            wall_took = _wall() - wall_start
            self.cycle_times.append((sim0.to_sec(), wall_took))
            if len(self.cycle_times) > 10000:
                del self.cycle_times[:5000]
            if done:
                return
            next_cycle = next_cycle + period
            now = rospy.Time.now()
            if now > next_cycle + period:
                took = now.to_sec() - wall0
                rospy.logwarn_throttle(
                    5.0, 'Control loop missed its desired rate of %.4fHz... the loop actually '
                    'took %.4f seconds' % (self.controller_frequency, took))
                next_cycle = now
            while rospy.Time.now() < next_cycle and not rospy.is_shutdown():
                rospy.sleep(min(0.01, period.to_sec()))
        self.server.set_aborted(MoveBaseResult(), 'Aborting on the goal because the node has '
                                'been killed')

    def _execute_cycle(self, goal):
        pose = self._robot_pose_stamped(self.planner_costmap)
        position = None
        if pose is not None:
            self.server.publish_feedback(MoveBaseFeedback(base_position=pose))
            position = (pose.pose.position.x, pose.pose.position.y)
        self._cycle_pose = pose
        result = self.core.cycle(position, self.controller_costmap.is_current())
        if result is None:
            return False
        if result.status == core.SUCCEEDED:
            self.server.set_succeeded(MoveBaseResult(), result.text)
        else:
            self.server.set_aborted(MoveBaseResult(), result.text)
        return True

    # ---- services --------------------------------------------------------------------------
    def _make_plan_service(self, req):
        if self.server.is_active():
            rospy.logerr('move_base must be in an inactive state to make a plan for an '
                         'external user')
            return None
        resp = GetPlanResponse()
        resp.plan.header.frame_id = self.planner_costmap.global_frame
        resp.plan.header.stamp = rospy.Time.now()
        if req.start.header.frame_id:
            start = self._goal_to_global_frame(req.start)
        else:
            start = self._robot_pose_stamped(self.planner_costmap)
            if start is None:
                rospy.logerr('move_base cannot make a plan for you because it could not get '
                             'the start pose of the robot')
                return None
        goal = self._goal_to_global_frame(req.goal)
        if self.make_plan_clear_costmap:
            self.planner_costmap.clear_outside(self.conservative_reset_dist,
                                               (start.pose.position.x, start.pose.position.y))
        plan = self.planner.make_plan(start, goal, req.tolerance)
        if plan and self.make_plan_add_unreachable_goal and \
                conv.distance(plan[-1], goal) > 1e-6:
            plan.append(goal)
        resp.plan.poses = plan
        return resp

    def _clear_costmaps_service(self, _req):
        self.planner_costmap.reset_layers()
        self.controller_costmap.reset_layers()
        return EmptyResponse()


class _RosOutputs(core.Outputs):
    """The core's outputs as the original sends them: cmd_vel, ~recovery_status, rosout."""

    def __init__(self, node):
        self.node = node

    def zero_velocity(self):
        self.node.publish_zero_velocity()

    def command(self, cmd):
        self.node.vel_pub.publish(cmd)

    def recovery_status(self, number, total, name):
        st = RecoveryStatus()
        if self.node._cycle_pose is not None:
            st.pose_stamped = self.node._cycle_pose
        st.current_recovery_number = number
        st.total_number_of_recoveries = total
        st.recovery_behavior_name = name
        self.node.recovery_status_pub.publish(st)

    def debug(self, msg):
        rospy.logdebug(msg)

    def error(self, msg):
        rospy.logerr(msg)

    def warn_throttle(self, period, msg):
        rospy.logwarn_throttle(period, '[%s]:%s' % (rospy.get_name(), msg))


def _wall():
    import time
    return time.monotonic()
