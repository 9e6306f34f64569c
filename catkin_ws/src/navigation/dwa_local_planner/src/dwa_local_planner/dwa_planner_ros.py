"""DWAPlannerROS: the dynamic window variant, on base_local_planner's trajectory core with
dwa_local_planner's parameter names and defaults (DWAPlanner.cfg)."""
import rospy

from base_local_planner.trajectory_planner import TrajectoryParams
from base_local_planner.trajectory_planner_ros import TrajectoryPlannerROS


class DWAPlannerROS(TrajectoryPlannerROS):
    def read_params(self, prm):
        p = TrajectoryParams(dwa=True, holonomic_robot=False)
        max_trans = float(prm.get('max_vel_trans', 0.55, 'max_trans_vel'))
        p.max_vel_x = min(float(prm.get('max_vel_x', 0.55)), max_trans)
        p.min_vel_x = float(prm.get('min_vel_x', 0.0))
        max_rot = float(prm.get('max_vel_theta', 1.0, 'max_rot_vel'))
        min_rot = float(prm.get('min_vel_theta', 0.4, 'min_rot_vel'))
        p.max_vel_theta = max_rot
        p.min_vel_theta = -max_rot
        p.min_in_place_vel_theta = min_rot
        p.acc_lim_x = float(prm.get('acc_lim_x', 2.5))
        p.acc_lim_y = float(prm.get('acc_lim_y', 2.5))
        p.acc_lim_theta = float(prm.get('acc_lim_theta', 3.2, 'acc_lim_th'))
        p.sim_time = float(prm.get('sim_time', 1.7))
        p.sim_granularity = float(prm.get('sim_granularity', 0.025))
        p.angular_sim_granularity = float(prm.get('angular_sim_granularity', 0.1))
        p.vx_samples = max(1, int(prm.get('vx_samples', 3)))
        p.vtheta_samples = max(1, int(prm.get('vth_samples', 20, 'vtheta_samples')))
        p.pdist_scale = float(prm.get('path_distance_bias', 0.6, 'pdist_scale'))
        p.gdist_scale = float(prm.get('goal_distance_bias', 0.8, 'gdist_scale'))
        p.occdist_scale = float(prm.get('occdist_scale', 0.01))
        p.heading_lookahead = float(prm.get('forward_point_distance', 0.325))
        p.oscillation_reset_dist = float(prm.get('oscillation_reset_dist', 0.05))
        p.meter_scoring = True          # DWA scores in metres (scaled by the resolution)
        ctrl_key = rospy.search_param('controller_frequency')
        ctrl = float(rospy.get_param(ctrl_key, 20.0)) if ctrl_key else 20.0
        p.sim_period = 1.0 / ctrl if ctrl > 0 else 0.05
        self.p = p
        self.xy_goal_tolerance = float(prm.get('xy_goal_tolerance', 0.1))
        self.yaw_goal_tolerance = float(prm.get('yaw_goal_tolerance', 0.1))
        self.latch_xy_goal_tolerance = bool(prm.get('latch_xy_goal_tolerance', False))
        self.prune_plan = bool(prm.get('prune_plan', True))
        self.trans_stopped_vel = float(prm.get('trans_stopped_vel', 0.1))
        self.rot_stopped_vel = float(prm.get('theta_stopped_vel', 0.1, 'rot_stopped_vel'))
        self.odom_topic = str(prm.get('odom_topic', 'odom'))
