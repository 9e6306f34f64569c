"""ClearCostmapRecovery: resets the obstacle layers of the costmaps outside a square of
reset_distance around the robot."""
import rospy

from nav_core import RecoveryBehavior


class ClearCostmapRecovery(RecoveryBehavior):
    def initialize(self, name, tf_buffer, global_costmap, local_costmap):
        self.name = name
        ns = rospy.resolve_name('~' + name)
        self.global_costmap = global_costmap
        self.local_costmap = local_costmap
        self.reset_distance = float(rospy.get_param(ns + '/reset_distance', 3.0))
        self.affected_maps = str(rospy.get_param(ns + '/affected_maps', 'both'))
        self.force_updating = bool(rospy.get_param(ns + '/force_updating', False))
        if self.affected_maps not in ('local', 'global', 'both'):
            rospy.logerr('%s/affected_maps must be set to local, global or both' % ns)
            self.affected_maps = 'both'

    def run_behavior(self):
        rospy.logwarn('Clearing %s costmap%s outside a square (%.2fm) large centered on the '
                      'robot.' % (self.affected_maps, 's' if self.affected_maps == 'both' else '',
                                  self.reset_distance))
        maps = []
        if self.affected_maps in ('global', 'both'):
            maps.append(self.global_costmap)
        if self.affected_maps in ('local', 'both'):
            maps.append(self.local_costmap)
        for cm in maps:
            pose = cm.get_robot_pose()
            if pose is None:
                rospy.logerr('Cannot clear map because pose cannot be retrieved')
                continue
            cm.clear_outside(self.reset_distance, pose)
            if self.force_updating:
                cm.update_map()
