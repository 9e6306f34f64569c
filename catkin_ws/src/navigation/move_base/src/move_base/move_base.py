"""MoveBase: the move_base action server (the original's state machine: PLANNING,
CONTROLLING, CLEARING; a planner thread; recovery behaviours)."""
import math
import sys
import threading

import actionlib
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped, Twist
from move_base_msgs.msg import (MoveBaseAction, MoveBaseFeedback, MoveBaseGoal,
                                MoveBaseResult, RecoveryStatus)
from nav_msgs.srv import GetPlan, GetPlanResponse
from std_srvs.srv import Empty, EmptyResponse

import nav_core
from costmap_2d.costmap_2d_ros import Costmap2DROS
from costmap_2d.params import CostmapParamError

from . import conversions as conv

PLANNING, CONTROLLING, CLEARING = 'PLANNING', 'CONTROLLING', 'CLEARING'
PLANNING_R, CONTROLLING_R, OSCILLATION_R = 'PLANNING_R', 'CONTROLLING_R', 'OSCILLATION_R'


class MoveBase:
    def __init__(self):
        P = lambda name, default: rospy.get_param('~' + name, default)  # noqa: E731
        self.global_planner_name = str(P('base_global_planner', 'navfn/NavfnROS'))
        self.local_planner_name = str(P('base_local_planner',
                                        'base_local_planner/TrajectoryPlannerROS'))
        self.robot_base_frame = str(P('global_costmap/robot_base_frame', 'base_link'))
        self.global_frame = str(P('global_costmap/global_frame', 'map'))
        self.planner_frequency = float(P('planner_frequency', 0.0))
        self.controller_frequency = float(P('controller_frequency', 20.0))
        self.planner_patience = float(P('planner_patience', 5.0))
        self.controller_patience = float(P('controller_patience', 15.0))
        self.max_planning_retries = int(P('max_planning_retries', -1))
        self.oscillation_timeout = float(P('oscillation_timeout', 0.0))
        self.oscillation_distance = float(P('oscillation_distance', 0.5))
        self.conservative_reset_dist = float(P('conservative_reset_dist', 3.0))
        self.clearing_rotation_allowed = bool(P('clearing_rotation_allowed', True))
        self.recovery_behavior_enabled = bool(P('recovery_behavior_enabled', True))
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

        self.lock = threading.RLock()
        self.planner_cond = threading.Condition(self.lock)
        self.run_planner = False
        self.planner_goal = None
        self.planner_plan = None
        self.latest_plan = None
        self.new_global_plan = False
        self.state = PLANNING
        self.recovery_trigger = PLANNING_R
        self.recovery_index = 0
        self.planning_retries = 0
        self.last_valid_plan = rospy.Time.now()
        self.last_valid_control = rospy.Time.now()
        self.last_oscillation_reset = rospy.Time.now()
        self.oscillation_pose = None
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
        with self.lock:
            self.run_planner = False
            self.state = PLANNING
            self.recovery_index = 0
            self.recovery_trigger = PLANNING_R
        self.publish_zero_velocity()

    # ---- the planner thread ----------------------------------------------------------------
    def _plan_thread(self):
        wait_for_wake = False
        while not rospy.is_shutdown():
            with self.lock:
                while (wait_for_wake or not self.run_planner) and not rospy.is_shutdown():
                    self.planner_cond.wait(0.2)
                    wait_for_wake = False
                    if self.run_planner:
                        break
                if rospy.is_shutdown():
                    return
                goal = self.planner_goal
                start_time = rospy.Time.now()
            plan = self.make_plan(goal) if goal is not None else []
            with self.lock:
                if plan:
                    self.latest_plan = plan
                    self.last_valid_plan = rospy.Time.now()
                    self.planning_retries = 0
                    self.new_global_plan = True
                    if self.run_planner:
                        self.state = CONTROLLING
                    if self.planner_frequency <= 0:
                        self.run_planner = False
                elif self.state == PLANNING:
                    attempt_end = self.last_valid_plan + rospy.Duration(self.planner_patience)
                    self.planning_retries += 1
                    retries_exceeded = (self.max_planning_retries >= 0 and
                                        self.planning_retries > self.max_planning_retries)
                    if self.run_planner and (rospy.Time.now() > attempt_end or retries_exceeded):
                        self.state = CLEARING
                        self.run_planner = False
                        self.publish_zero_velocity()
                        self.recovery_trigger = PLANNING_R
            if self.planner_frequency > 0:
                end = start_time + rospy.Duration(1.0 / self.planner_frequency)
                while rospy.Time.now() < end and not rospy.is_shutdown():
                    rospy.sleep(0.02)
            elif not plan:
                # retry promptly, but let the controller loop run
                rospy.sleep(0.05)

    # ---- the action ------------------------------------------------------------------------
    def _start_goal(self, goal):
        goal = self._goal_to_global_frame(goal)
        with self.lock:
            self.planner_goal = goal
            self.run_planner = True
            self.state = PLANNING
            self.recovery_index = 0
            self.recovery_trigger = PLANNING_R
            self.planning_retries = 0
            now = rospy.Time.now()
            self.last_valid_control = now
            self.last_valid_plan = now
            self.last_oscillation_reset = now
            self.planner_cond.notify_all()
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
        if pose is not None:
            self.server.publish_feedback(MoveBaseFeedback(base_position=pose))
            now = rospy.Time.now()
            if self.oscillation_pose is None or conv.distance(pose, self.oscillation_pose) >= \
                    self.oscillation_distance:
                self.last_oscillation_reset = now
                self.oscillation_pose = pose
                if self.recovery_trigger == OSCILLATION_R:
                    self.recovery_index = 0
        if not self.controller_costmap.is_current():
            rospy.logwarn_throttle(1.0, '[%s]:Sensor data is out of date, we\'re not going to '
                                   'allow commanding of the base for safety'
                                   % rospy.get_name())
            self.publish_zero_velocity()
            return False
        with self.lock:
            if self.new_global_plan:
                self.new_global_plan = False
                plan = self.latest_plan
                if not self.tc.set_plan(plan):
                    rospy.logerr('Failed to pass global plan to the controller, aborting.')
                    self.reset_state()
                    self.server.set_aborted(MoveBaseResult(), 'Failed to pass global plan to '
                                            'the controller.')
                    return True
                if self.recovery_trigger == PLANNING_R:
                    self.recovery_index = 0
            state = self.state
        if state == PLANNING:
            with self.lock:
                self.run_planner = True
                self.planner_cond.notify_all()
            return False
        if state == CONTROLLING:
            if self.tc.is_goal_reached():
                rospy.logdebug('Goal reached!')
                self.reset_state()
                self.server.set_succeeded(MoveBaseResult(), 'Goal reached.')
                return True
            now = rospy.Time.now()
            if self.oscillation_timeout > 0 and self.last_oscillation_reset + \
                    rospy.Duration(self.oscillation_timeout) < now:
                self.publish_zero_velocity()
                with self.lock:
                    self.state = CLEARING
                    self.recovery_trigger = OSCILLATION_R
                return False
            cmd = self.tc.compute_velocity_commands()
            if cmd is not None:
                self.last_valid_control = rospy.Time.now()
                self.vel_pub.publish(cmd)
                if self.recovery_trigger == CONTROLLING_R:
                    self.recovery_index = 0
            else:
                rospy.logdebug('The local planner could not find a valid plan.')
                attempt_end = self.last_valid_control + rospy.Duration(self.controller_patience)
                with self.lock:
                    if rospy.Time.now() > attempt_end:
                        self.publish_zero_velocity()
                        self.state = CLEARING
                        self.recovery_trigger = CONTROLLING_R
                    else:
                        self.last_valid_plan = rospy.Time.now()
                        self.planning_retries = 0
                        self.state = PLANNING
                        self.publish_zero_velocity()
                        self.run_planner = True
                        self.planner_cond.notify_all()
            return False
        # CLEARING
        if self.recovery_behavior_enabled and self.recovery_index < len(self.recovery_behaviors):
            b = self.recovery_behaviors[self.recovery_index]
            rospy.logdebug('Executing behavior %u of %u' % (self.recovery_index + 1,
                                                             len(self.recovery_behaviors)))
            st = RecoveryStatus()
            if pose is not None:
                st.pose_stamped = pose
            st.current_recovery_number = self.recovery_index
            st.total_number_of_recoveries = len(self.recovery_behaviors)
            st.recovery_behavior_name = b.behavior_name
            self.recovery_status_pub.publish(st)
            b.run_behavior()
            with self.lock:
                self.last_oscillation_reset = rospy.Time.now()
                self.state = PLANNING
                self.run_planner = True
                self.planning_retries = 0
                self.recovery_index += 1
                self.planner_cond.notify_all()
            return False
        rospy.logdebug('All recovery behaviors have failed, locking the planner and disabling it.')
        with self.lock:
            self.run_planner = False
            trigger = self.recovery_trigger
        if trigger == CONTROLLING_R:
            rospy.logerr('Aborting because a valid control could not be found. Even after '
                         'executing all recovery behaviors')
            text = 'Failed to find a valid control. Even after executing recovery behaviors.'
        elif trigger == PLANNING_R:
            rospy.logerr('Aborting because a valid plan could not be found. Even after '
                         'executing all recovery behaviors')
            text = 'Failed to find a valid plan. Even after executing recovery behaviors.'
        else:
            rospy.logerr('Aborting because the robot appears to be oscillating over and over. '
                         'Even after executing all recovery behaviors')
            text = 'Robot is oscillating. Even after executing recovery behaviors.'
        self.reset_state()
        self.server.set_aborted(MoveBaseResult(), text)
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


def _wall():
    import time
    return time.monotonic()
