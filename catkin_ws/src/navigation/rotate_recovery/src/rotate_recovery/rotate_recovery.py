"""RotateRecovery: an in-place 360° turn, refused when the local costmap says the footprint
would collide."""
import math

import rospy
from geometry_msgs.msg import Twist

from nav_core import RecoveryBehavior

LETHAL = 254
INSCRIBED = 253
NO_INFORMATION = 255


class RotateRecovery(RecoveryBehavior):
    def initialize(self, name, tf_buffer, global_costmap, local_costmap):
        self.name = name
        ns = rospy.resolve_name('~' + name)
        self.local_costmap = local_costmap
        self.sim_granularity = float(rospy.get_param(ns + '/sim_granularity', 0.017))
        self.frequency = float(rospy.get_param(ns + '/frequency', 20.0))
        bp = rospy.resolve_name('~TrajectoryPlannerROS')
        self.acc_lim_th = float(rospy.get_param(bp + '/acc_lim_theta',
                                                rospy.get_param(bp + '/acc_lim_th', 3.2)))
        self.max_rotational_vel = float(rospy.get_param(
            bp + '/max_vel_theta', rospy.get_param(bp + '/max_rotational_vel', 1.0)))
        self.min_rotational_vel = float(rospy.get_param(
            bp + '/min_in_place_vel_theta', rospy.get_param(bp + '/min_in_place_rotational_vel',
                                                            0.4)))
        self.tolerance = float(rospy.get_param(bp + '/yaw_goal_tolerance', 0.10))
        self.vel_pub = rospy.Publisher('cmd_vel', Twist, queue_size=10)

    def _arc_cost(self, x, y, th0, arc):
        """The worst footprintCost (base_local_planner's CostmapModel on the local costmap)
        at the angles th0 .. th0 + arc every sim_granularity: -1 when the footprint would
        touch a lethal or unknown cell or leave the map, as the original checks."""
        import numpy as np
        from base_local_planner import native
        cm = self.local_costmap
        angles = th0 + np.arange(0.0, max(arc, 0.0), self.sim_granularity)
        if len(angles) == 0:
            return 0.0
        with cm.lock:
            grid = cm.costmap
            fp = np.asarray(cm.layered.footprint, dtype=float).reshape(-1, 2)
            costs = native.footprint_costs(grid.data, grid.origin_x, grid.origin_y,
                                           grid.resolution, fp, np.full((len(angles), 1), x),
                                           np.full((len(angles), 1), y), angles[:, None])
        return float(-1.0 if (costs < 0).any() else costs.max())

    def run_behavior(self):
        rospy.logwarn('Rotate recovery behavior started.')
        rate = rospy.Rate(self.frequency)
        pose = self.local_costmap.get_robot_pose()
        if pose is None:
            rospy.logerr('Unable to get the robot pose for the rotate recovery')
            return
        start_angle = current_angle = pose[2]
        got_180 = False

        def sad(a, b):
            return math.atan2(math.sin(b - a), math.cos(b - a))
        while not rospy.is_shutdown() and (
                not got_180 or abs(sad(current_angle, start_angle)) > self.tolerance):
            pose = self.local_costmap.get_robot_pose()
            if pose is None:
                break
            current_angle = pose[2]
            if not got_180:
                to_180 = abs(sad(current_angle, start_angle + math.pi))
                dist_left = math.pi + to_180
                if to_180 < self.tolerance:
                    got_180 = True
            else:
                dist_left = abs(sad(current_angle, start_angle))
            cost = self._arc_cost(pose[0], pose[1], current_angle, dist_left)
            if cost < 0.0:
                rospy.logerr('Rotate recovery can\'t rotate in place because there is a '
                             'potential collision. Cost: %.2f' % cost)
                break
            vel = math.sqrt(2 * self.acc_lim_th * dist_left)
            vel = min(max(vel, self.min_rotational_vel), self.max_rotational_vel)
            cmd = Twist()
            cmd.angular.z = vel
            self.vel_pub.publish(cmd)
            rate.sleep()
        self.vel_pub.publish(Twist())
