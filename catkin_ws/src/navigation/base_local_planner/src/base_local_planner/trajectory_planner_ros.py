"""TrajectoryPlannerROS: the trajectory rollout planner behind nav_core's local planner
interface (parameters, odometry, the plan in the local frame, goal checks)."""
import math
import threading

import numpy as np
import rospy
import tf2_ros
from nav_msgs.msg import Odometry, Path

from nav_core import BaseLocalPlanner

from . import conversions as conv
from .trajectory_planner import LocalGrid, TrajectoryParams, TrajectoryPlanner


def _angle(a):
    return math.atan2(math.sin(a), math.cos(a))


def rotate_to_goal_speed(v, p):
    """rotateToGoal's last step: min_in_place_vel_theta re-enforced over the acceleration
    limits, within [min_vel_theta, max_vel_theta] (so a min_in_place_vel_theta above
    max_vel_theta, as the diploma's 0.9 over 0.85, turns at max_vel_theta)."""
    if v > 0.0:
        return min(p.max_vel_theta, max(p.min_in_place_vel_theta, v))
    return max(p.min_vel_theta, min(-p.min_in_place_vel_theta, v))


class _Params:
    """Reads ~<name>/param with legacy fallbacks, keeping track of what was set."""

    def __init__(self, ns):
        self.ns = ns

    def has(self, name):
        return rospy.has_param(self.ns + '/' + name)

    def get(self, name, default, *legacy):
        for n in (name,) + legacy:
            if self.has(n):
                return rospy.get_param(self.ns + '/' + n)
        return default


class TrajectoryPlannerROS(BaseLocalPlanner):
    # the defaults of this planner's parameter set (TrajectoryParams holds them)
    DWA_DEFAULT = False

    def __init__(self):
        self.initialized = False

    def initialize(self, name, tf_buffer, costmap_ros):
        self.name = name
        self.tf_buffer = tf_buffer
        self.costmap_ros = costmap_ros
        self.ns = rospy.resolve_name('~' + name)
        self.read_params(_Params(self.ns))
        self.planner = TrajectoryPlanner(self.p, costmap_ros.layered.footprint)
        self.global_plan = []
        self.reached_goal = False
        self.xy_tolerance_latch = False
        self.rotating_to_goal = False
        self.lock = threading.Lock()
        self.velocity = (0.0, 0.0, 0.0)
        self.odom_sub = rospy.Subscriber(self.odom_topic, Odometry, self._odom_cb, queue_size=1)
        self.g_plan_pub = rospy.Publisher(self.ns + '/global_plan', Path, queue_size=1)
        self.l_plan_pub = rospy.Publisher(self.ns + '/local_plan', Path, queue_size=1)
        self.initialized = True

    def read_params(self, prm):
        p = TrajectoryParams()
        p.max_vel_x = float(prm.get('max_vel_x', p.max_vel_x))
        p.min_vel_x = float(prm.get('min_vel_x', p.min_vel_x))
        p.max_vel_theta = float(prm.get('max_vel_theta', p.max_vel_theta, 'max_rotational_vel'))
        p.min_vel_theta = float(prm.get('min_vel_theta', -p.max_vel_theta))
        p.min_in_place_vel_theta = float(prm.get('min_in_place_vel_theta',
                                                 p.min_in_place_vel_theta,
                                                 'min_in_place_rotational_vel'))
        p.acc_lim_x = float(prm.get('acc_lim_x', p.acc_lim_x))
        p.acc_lim_y = float(prm.get('acc_lim_y', p.acc_lim_y))
        p.acc_lim_theta = float(prm.get('acc_lim_theta', p.acc_lim_theta, 'acc_lim_th'))
        p.sim_time = float(prm.get('sim_time', p.sim_time))
        p.sim_granularity = float(prm.get('sim_granularity', p.sim_granularity))
        p.angular_sim_granularity = float(prm.get('angular_sim_granularity', p.sim_granularity))
        p.vx_samples = int(prm.get('vx_samples', p.vx_samples))
        p.vtheta_samples = int(prm.get('vtheta_samples', p.vtheta_samples))
        p.pdist_scale = float(prm.get('path_distance_bias', p.pdist_scale, 'pdist_scale'))
        p.gdist_scale = float(prm.get('goal_distance_bias', p.gdist_scale, 'gdist_scale'))
        p.occdist_scale = float(prm.get('occdist_scale', p.occdist_scale))
        p.heading_lookahead = float(prm.get('heading_lookahead', p.heading_lookahead))
        p.oscillation_reset_dist = float(prm.get('oscillation_reset_dist',
                                                 p.oscillation_reset_dist))
        p.escape_reset_dist = float(prm.get('escape_reset_dist', p.escape_reset_dist))
        p.escape_reset_theta = float(prm.get('escape_reset_theta', p.escape_reset_theta))
        p.escape_vel = float(prm.get('escape_vel', p.escape_vel))
        p.holonomic_robot = bool(prm.get('holonomic_robot', p.holonomic_robot))
        p.dwa = bool(prm.get('dwa', self.DWA_DEFAULT))
        if not prm.has('meter_scoring'):
            rospy.logwarn('Trajectory Rollout planner initialized with param meter_scoring not '
                          'set. Set it to true to make your settings robust against changes of '
                          'costmap resolution.')
        p.meter_scoring = bool(prm.get('meter_scoring', False))
        ctrl_key = rospy.search_param('controller_frequency')
        ctrl = float(rospy.get_param(ctrl_key, 20.0)) if ctrl_key else 20.0
        p.sim_period = 1.0 / ctrl if ctrl > 0 else 0.05
        if p.vx_samples <= 0:
            rospy.logwarn('You\'ve specified that you don\'t want any samples in the x '
                          'dimension. We\'ll at least assume that you want to sample one value'
                          '... so we\'re going to set vx_samples to 1 instead')
            p.vx_samples = 1
        if p.vtheta_samples <= 0:
            rospy.logwarn('You\'ve specified that you don\'t want any samples in the theta '
                          'dimension. We\'ll at least assume that you want to sample one value'
                          '... so we\'re going to set vtheta_samples to 1 instead')
            p.vtheta_samples = 1
        self.p = p
        self.xy_goal_tolerance = float(prm.get('xy_goal_tolerance', 0.10))
        self.yaw_goal_tolerance = float(prm.get('yaw_goal_tolerance', 0.05))
        self.latch_xy_goal_tolerance = bool(prm.get('latch_xy_goal_tolerance', False))
        self.prune_plan = bool(prm.get('prune_plan', True))
        self.trans_stopped_vel = float(prm.get('trans_stopped_vel', 0.1))
        self.rot_stopped_vel = float(prm.get('rot_stopped_vel', 0.1))
        self.odom_topic = str(prm.get('odom_topic', 'odom'))

    def _odom_cb(self, msg):
        with self.lock:
            self.velocity = conv.odom_velocity(msg)

    # ---- nav_core interface --------------------------------------------------------------
    def set_plan(self, plan):
        if not self.initialized:
            rospy.logerr('This planner has not been initialized, please call initialize() '
                         'before using this planner')
            return False
        self.global_plan = list(plan)
        # a new plan (a new goal, or a replan after a failed control) starts without the
        # previous one's barred turns (as DWAPlanner::setPlan resets its oscillation flags)
        self.planner.reset_oscillation_flags()
        self.xy_tolerance_latch = False
        self.reached_goal = False
        self.rotating_to_goal = False
        return True

    def is_goal_reached(self):
        return self.reached_goal

    def _local_state(self):
        pose = self.costmap_ros.get_robot_pose()
        if pose is None or not self.global_plan:
            return None
        lf = self.costmap_ros.global_frame
        pf = self.global_plan[0].header.frame_id.lstrip('/') or lf
        try:
            t = self.tf_buffer.lookup_transform(lf, pf, rospy.Time(0), rospy.Duration(0.1))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException) as e:
            rospy.logwarn_throttle(1.0, 'Failed to transform the global plan from %s to %s: %s'
                                   % (pf, lf, e))
            return None
        plan = conv.plan_to_array(self.global_plan, conv.transform_to_xyyaw(t.transform))
        return pose, plan

    def _transform_plan(self, pose, plan):
        """The part of the plan around the robot inside the local costmap (with pruning of
        the part already driven)."""
        cm = self.costmap_ros.costmap
        half = max(cm.size_x, cm.size_y) * cm.resolution / 2.0
        d = np.hypot(plan[:, 0] - pose[0], plan[:, 1] - pose[1])
        # the closest point among the first ones within the window
        within = np.nonzero(d <= half)[0]
        if len(within) == 0:
            return plan[:0]
        start = within[0]
        # skip the driven part: the nearest point in the first stretch within the window
        run_end = start
        while run_end + 1 < len(plan) and d[run_end + 1] <= half:
            run_end += 1
        nearest = start + int(np.argmin(d[start:run_end + 1]))
        if self.prune_plan and nearest > 0:
            self.global_plan = self.global_plan[nearest:]
            plan = plan[nearest:]
            run_end -= nearest
            nearest = 0
        return plan[nearest:run_end + 1]

    def compute_velocity_commands(self):
        """geometry_msgs/Twist, or None when no valid command exists."""
        if not self.initialized:
            rospy.logerr('This planner has not been initialized, please call initialize() '
                         'before using this planner')
            return None
        st = self._local_state()
        if st is None:
            return None
        pose, plan = st
        goal = plan[-1]
        local = self._transform_plan(pose, plan)
        if len(local) == 0:
            rospy.logwarn_throttle(1.0, 'Received an empty transformed plan.')
            return None
        with self.lock:
            vel = self.velocity
        lf = self.costmap_ros.global_frame
        with self.costmap_ros.lock:
            cm = self.costmap_ros.costmap
            grid = LocalGrid(cm.data.copy(), cm.resolution, cm.origin_x, cm.origin_y)
        x, y, th = pose
        if self.xy_tolerance_latch or math.hypot(goal[0] - x, goal[1] - y) <= \
                self.xy_goal_tolerance:
            if self.latch_xy_goal_tolerance:
                self.xy_tolerance_latch = True
            self.planner.update_plan(grid, local[:, :2], pose)
            ang = _angle(goal[2] - th)
            if abs(ang) <= self.yaw_goal_tolerance:
                self.reached_goal = True
                self.rotating_to_goal = False
                self.xy_tolerance_latch = False
                self._publish(local, np.zeros((0, 3)), lf)
                return conv.twist(0, 0, 0)
            if not self.rotating_to_goal and not self._stopped(vel):
                cmd = self._stop_with_acc_limits(pose, vel)
            else:
                self.rotating_to_goal = True
                cmd = self._rotate_to_goal(pose, vel, goal[2])
            self._publish(local, np.zeros((0, 3)), lf)
            return cmd
        self.planner.update_plan(grid, local[:, :2], pose)
        vx, vy, vth, cost, pts = self.planner.find_best_path(x, y, th, *vel)
        self._publish(local, pts, lf)
        if cost < 0:
            rospy.logdebug('The rollout planner failed to find a valid plan. This means that '
                           'the footprint of the robot was in collision for all simulated '
                           'trajectories.')
            return None
        return conv.twist(vx, vy, vth)

    def _stopped(self, vel):
        return abs(vel[2]) <= self.rot_stopped_vel and abs(vel[0]) <= self.trans_stopped_vel \
            and abs(vel[1]) <= self.trans_stopped_vel

    def _stop_with_acc_limits(self, pose, vel):
        p = self.p
        vx = math.copysign(max(0.0, abs(vel[0]) - p.acc_lim_x * p.sim_period), vel[0])
        vy = math.copysign(max(0.0, abs(vel[1]) - p.acc_lim_y * p.sim_period), vel[1])
        vth = math.copysign(max(0.0, abs(vel[2]) - p.acc_lim_theta * p.sim_period), vel[2])
        if self.planner.check_trajectory(pose[0], pose[1], pose[2], *vel, vx, vy, vth):
            return conv.twist(vx, vy, vth)
        return conv.twist(0, 0, 0)

    def _rotate_to_goal(self, pose, vel, goal_th):
        p = self.p
        ang = _angle(goal_th - pose[2])
        if ang > 0:
            v = min(p.max_vel_theta, max(p.min_in_place_vel_theta, ang))
        else:
            v = max(p.min_vel_theta, min(-p.min_in_place_vel_theta, ang))
        max_acc_vel = abs(vel[2]) + p.acc_lim_theta * p.sim_period
        min_acc_vel = abs(vel[2]) - p.acc_lim_theta * p.sim_period
        v = math.copysign(min(max(abs(v), min_acc_vel), max_acc_vel), v)
        v = math.copysign(min(math.sqrt(2 * p.acc_lim_theta * abs(ang)), abs(v)), v)
        v = rotate_to_goal_speed(v, p)
        if self.planner.check_trajectory(pose[0], pose[1], pose[2], *vel, 0.0, 0.0, v):
            return conv.twist(0.0, 0.0, v)
        return conv.twist(0, 0, 0)

    def _publish(self, local, pts, frame):
        self.g_plan_pub.publish(conv.array_to_path(local, frame))
        self.l_plan_pub.publish(conv.array_to_path(pts, frame))
