"""The `explore` node: frontiers from the costmap, the cheapest as a move_base goal, again and
again until none is left (explore_lite's behaviour, names and messages)."""
import threading

import actionlib
import numpy as np
import rospy
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from map_msgs.msg import OccupancyGridUpdate
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
from nav_msgs.msg import OccupancyGrid
from std_msgs.msg import Bool
from visualization_msgs.msg import MarkerArray

from explore_lite import convert, frontiers


class Explore:
    def __init__(self):
        p = rospy.get_param
        self.planner_frequency = float(p('~planner_frequency', 1.0))
        self.potential_scale = float(p('~potential_scale', 1e-3))
        self.orientation_scale = float(p('~orientation_scale', 0.0))   # unused, as in explore_lite
        self.gain_scale = float(p('~gain_scale', 1.0))
        self.min_frontier_size = float(p('~min_frontier_size', 0.5))
        self.visualize = bool(p('~visualize', False))
        self.robot_base_frame = p('~robot_base_frame', 'base_link')
        self.transform_tolerance = float(p('~transform_tolerance', 0.3))
        costmap_topic = p('~costmap_topic', 'costmap')
        updates_topic = p('~costmap_updates_topic', 'costmap_updates')
        if self.planner_frequency <= 0:
            rospy.logwarn('~planner_frequency %.3f is not positive; using 1.0', self.planner_frequency)
            self.planner_frequency = 1.0
        self.progress = frontiers.Progress(float(p('~progress_timeout', 30.0)))
        self.lock = threading.Lock()
        self.grid = None
        self.frame = None
        self.blacklist = None
        self.active = True
        self.finished = False
        self.tf = tf2_ros.Buffer()
        self.listener = tf2_ros.TransformListener(self.tf)
        self.markers = rospy.Publisher('~frontiers', MarkerArray, queue_size=10) if self.visualize else None
        rospy.Subscriber(costmap_topic, OccupancyGrid, self.on_costmap, queue_size=1)
        if updates_topic:
            rospy.Subscriber(updates_topic, OccupancyGridUpdate, self.on_update, queue_size=10)
        rospy.Subscriber('explore/resume', Bool, self.on_resume, queue_size=1)
        self.client = actionlib.SimpleActionClient('move_base', MoveBaseAction)
        rospy.loginfo('Waiting to connect to move_base server')
        while not self.client.wait_for_server(rospy.Duration(5.0)):
            if rospy.is_shutdown():
                return
            rospy.loginfo('Waiting to connect to move_base server')
        rospy.loginfo('Connected to move_base server')

    # --- inputs -------------------------------------------------------------------------
    def on_costmap(self, msg):
        with self.lock:
            self.grid = convert.grid_from_msg(msg)
            self.frame = msg.header.frame_id
            if self.blacklist is None:
                self.blacklist = frontiers.Blacklist(5 * msg.info.resolution)

    def on_update(self, msg):
        with self.lock:
            if self.grid is not None and not convert.apply_update(self.grid, msg):
                rospy.logwarn_throttle(5.0, 'costmap update %dx%d at (%d, %d) does not fit the '
                                       'costmap; waiting for a full one', msg.width, msg.height,
                                       msg.x, msg.y)

    def on_resume(self, msg):
        if msg.data and not self.active:
            rospy.loginfo('Exploration resumed.')
            self.active, self.finished = True, False
        elif not msg.data and self.active:
            self.stop()

    # --- planning -----------------------------------------------------------------------
    def robot_xy(self):
        try:
            t = self.tf.lookup_transform(self.frame, self.robot_base_frame, rospy.Time(0),
                                         rospy.Duration(self.transform_tolerance))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException) as e:
            rospy.logwarn_throttle(5.0, 'Could not get robot pose: no transform from %s to %s (%s)',
                                   self.frame, self.robot_base_frame, e)
            return None
        return t.transform.translation.x, t.transform.translation.y

    def make_plan(self):
        if not self.active or self.finished:
            return
        with self.lock:
            if self.grid is None:
                rospy.logwarn_throttle(5.0, 'Waiting for the costmap')
                return
            grid = frontiers.Grid(self.grid.costs.copy(), self.grid.resolution, self.grid.origin)
        pose = self.robot_xy()
        if pose is None:
            return
        try:
            found = frontiers.search(grid, pose, self.potential_scale, self.gain_scale,
                                     self.min_frontier_size)
        except ValueError as e:
            rospy.logwarn_throttle(5.0, 'Frontier search failed: %s', e)
            return
        rospy.logdebug('found %d frontiers', len(found))
        if self.markers is not None:
            self.markers.publish(convert.frontier_markers(found, self.frame, rospy.Time.now(),
                                                          self.blacklist))
        target = next((f for f in found if f.centroid not in self.blacklist), None)
        if target is None:
            rospy.loginfo('All frontiers traversed/tried out, stopping.')
            self.stop()
            self.finished = True
            return
        goal = target.centroid
        same = self.progress.goal is not None and np.hypot(
            goal[0] - self.progress.goal[0], goal[1] - self.progress.goal[1]) < 1e-9
        if self.progress.update(goal, target.min_distance, rospy.get_time()):
            self.blacklist.add(goal)
            rospy.logdebug('Adding current goal to black list')
            self.make_plan()
            return
        if same:
            return
        g = MoveBaseGoal()
        g.target_pose.header.frame_id = self.frame
        g.target_pose.header.stamp = rospy.Time.now()
        g.target_pose.pose.position.x, g.target_pose.pose.position.y = goal
        g.target_pose.pose.orientation.w = 1.0
        rospy.logdebug('Sending goal (%.2f, %.2f)', goal[0], goal[1])
        self.client.send_goal(g, done_cb=lambda status, result: self.reached(status, goal))

    def reached(self, status, goal):
        rospy.logdebug('Goal reached with status: %d', status)
        if status == GoalStatus.ABORTED:
            self.blacklist.add(goal)
            rospy.logdebug('Adding current goal to black list')
        # find a new goal at once rather than waiting for the next planning cycle
        threading.Thread(target=self.make_plan, daemon=True).start()

    def stop(self):
        self.client.cancel_all_goals()
        self.active = False
        rospy.loginfo('Exploration stopped.')

    def spin(self):
        rate = rospy.Rate(self.planner_frequency)
        while not rospy.is_shutdown():
            self.make_plan()
            try:
                rate.sleep()
            except rospy.ROSInterruptException:
                break
