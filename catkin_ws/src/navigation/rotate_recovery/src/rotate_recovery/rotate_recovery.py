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

    def _arc_legal(self, x, y, th0, arc):
        """True when the footprint outline touches no lethal or unknown cell at any angle
        th0 .. th0 + arc, every sim_granularity (the original's footprintCost loop)."""
        import numpy as np
        cm = self.local_costmap
        with cm.lock:
            grid = cm.costmap
            fp = np.asarray(cm.layered.footprint, dtype=float)
            if len(fp) < 3:
                fp = np.zeros((1, 2))
            outline = []
            for i in range(len(fp)):
                a, b = fp[i], fp[(i + 1) % len(fp)]
                n = max(1, int(np.ceil(np.hypot(*(b - a)) / (grid.resolution * 0.5))))
                outline.extend(a + (b - a) * k / n for k in range(n))
            outline = np.array(outline)
            angles = th0 + np.arange(0.0, max(arc, 0.0) + 1e-9, self.sim_granularity)
            c, s = np.cos(angles)[:, None], np.sin(angles)[:, None]
            px = x + outline[:, 0] * c - outline[:, 1] * s
            py = y + outline[:, 0] * s + outline[:, 1] * c
            mx, my, inside = grid.world_to_map_array(px, py)
            if not inside.all():
                return False
            vals = grid.data[my, mx]
        return not ((vals == LETHAL) | (vals == NO_INFORMATION)).any()

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
            if not self._arc_legal(pose[0], pose[1], current_angle, dist_left):
                rospy.logerr('Rotate recovery can\'t rotate in place because there is a '
                             'potential collision. Cost: -1.00')
                break
            vel = math.sqrt(2 * self.acc_lim_th * dist_left)
            vel = min(max(vel, self.min_rotational_vel), self.max_rotational_vel)
            cmd = Twist()
            cmd.angular.z = vel
            self.vel_pub.publish(cmd)
            rate.sleep()
        self.vel_pub.publish(Twist())
