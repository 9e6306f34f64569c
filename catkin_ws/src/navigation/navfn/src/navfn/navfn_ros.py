"""NavfnROS: the navfn global planner behind nav_core's interface, ~make_plan and ~plan."""

import rospy
from nav_msgs.msg import OccupancyGrid, Path
from nav_msgs.srv import GetPlan, GetPlanResponse

from nav_core import BaseGlobalPlanner

from . import conversions as conv
from .navfn import POT_HIGH, NavFn


class NavfnROS(BaseGlobalPlanner):
    def __init__(self):
        self.initialized = False

    def initialize(self, name, costmap_ros):
        self.name = name
        self.costmap_ros = costmap_ros
        ns = rospy.resolve_name('~' + name)
        self.allow_unknown = bool(rospy.get_param(ns + '/allow_unknown', True))
        self.default_tolerance = float(rospy.get_param(ns + '/default_tolerance', 0.0))
        self.visualize_potential = bool(rospy.get_param(ns + '/visualize_potential', False))
        self.planner_window_x = float(rospy.get_param(ns + '/planner_window_x', 0.0))
        self.planner_window_y = float(rospy.get_param(ns + '/planner_window_y', 0.0))
        self.use_astar = bool(rospy.get_param(ns + '/use_astar', False))
        self.navfn = NavFn(self.allow_unknown, self.use_astar)
        self.plan_pub = rospy.Publisher(ns + '/plan', Path, queue_size=1)
        self.potential_pub = rospy.Publisher(ns + '/potential', OccupancyGrid, queue_size=1) \
            if self.visualize_potential else None
        self.service = rospy.Service(ns + '/make_plan', GetPlan, self._make_plan_srv)
        self.initialized = True

    def _make_plan_srv(self, req):
        req.start.header.frame_id = req.start.header.frame_id or self.costmap_ros.global_frame
        plan = self.make_plan(req.start, req.goal, req.tolerance or self.default_tolerance)
        resp = GetPlanResponse()
        resp.plan.header.frame_id = self.costmap_ros.global_frame
        resp.plan.header.stamp = rospy.Time.now()
        resp.plan.poses = plan
        return resp

    def make_plan(self, start, goal, tolerance=None):
        if not self.initialized:
            rospy.logerr('This planner has not been initialized yet, but it is being used, '
                         'please call initialize() before use')
            return []
        tolerance = self.default_tolerance if tolerance is None else tolerance
        gf = self.costmap_ros.global_frame
        if conv.frame(goal) != gf:
            rospy.logerr('The goal pose passed to this planner must be in the %s frame.  It is '
                         'instead in the %s frame.' % (gf, conv.frame(goal)))
            return []
        if conv.frame(start) != gf:
            rospy.logerr('The start pose passed to this planner must be in the %s frame.  It is '
                         'instead in the %s frame.' % (gf, conv.frame(start)))
            return []
        with self.costmap_ros.lock:
            cm = self.costmap_ros.costmap
            data = cm.data.copy()
            res, ox, oy = cm.resolution, cm.origin_x, cm.origin_y
            s = cm.world_to_map(start.pose.position.x, start.pose.position.y)
            g = cm.world_to_map(goal.pose.position.x, goal.pose.position.y)
        if s is None:
            rospy.logwarn('The robot\'s start position is off the global costmap. Planning will '
                          'always fail, are you sure the robot has been properly localized?')
            return []
        if g is None:
            rospy.logwarn_throttle(1.0, 'The goal sent to the navfn planner is off the global '
                                   'costmap. Planning will always fail to this goal.')
            return []
        cells = self.navfn.plan(data, s, g, tolerance / res)
        if self.potential_pub is not None and self.navfn.potential is not None:
            self.potential_pub.publish(conv.potential_to_grid(
                self.navfn.potential, POT_HIGH, res, ox, oy, gf))
        if not cells:
            self.publish_plan([], gf)
            return []
        # cell coordinates -> world (cell centres); then the goal pose itself, as NavfnROS
        plan = [conv.pose_stamped(gf, ox + (cx + 0.5) * res, oy + (cy + 0.5) * res)
                for cx, cy in cells]
        goal_copy = conv.pose_stamped(gf, goal.pose.position.x, goal.pose.position.y,
                                      goal.pose.orientation)
        if plan:
            plan[-1] = goal_copy
        self.publish_plan(plan, gf)
        return plan

    def publish_plan(self, plan, frame):
        self.plan_pub.publish(conv.path(plan, frame))
