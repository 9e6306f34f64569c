// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/posvel_command_interface.h>
#include <hardware_interface/posvelacc_command_interface.h>
#include <pluginlib/class_list_macros.hpp>
#include <trajectory_interface/quintic_spline_segment.h>

#include <joint_trajectory_controller/joint_trajectory_controller.h>

namespace position_controllers
{
/// Joint trajectory controller commanding positions.
typedef joint_trajectory_controller::JointTrajectoryController<trajectory_interface::QuinticSplineSegment<double>,
                                                               hardware_interface::PositionJointInterface>
    JointTrajectoryController;
}  // namespace position_controllers

namespace velocity_controllers
{
/// Joint trajectory controller commanding velocities (PID per joint, gains/<joint>).
typedef joint_trajectory_controller::JointTrajectoryController<trajectory_interface::QuinticSplineSegment<double>,
                                                               hardware_interface::VelocityJointInterface>
    JointTrajectoryController;
}  // namespace velocity_controllers

namespace effort_controllers
{
/// Joint trajectory controller commanding efforts (PID per joint, gains/<joint>).
typedef joint_trajectory_controller::JointTrajectoryController<trajectory_interface::QuinticSplineSegment<double>,
                                                               hardware_interface::EffortJointInterface>
    JointTrajectoryController;
}  // namespace effort_controllers

namespace pos_vel_controllers
{
/// Joint trajectory controller commanding positions and velocities.
typedef joint_trajectory_controller::JointTrajectoryController<trajectory_interface::QuinticSplineSegment<double>,
                                                               hardware_interface::PosVelJointInterface>
    JointTrajectoryController;
}  // namespace pos_vel_controllers

namespace pos_vel_acc_controllers
{
/// Joint trajectory controller commanding positions, velocities and accelerations.
typedef joint_trajectory_controller::JointTrajectoryController<trajectory_interface::QuinticSplineSegment<double>,
                                                               hardware_interface::PosVelAccJointInterface>
    JointTrajectoryController;
}  // namespace pos_vel_acc_controllers

PLUGINLIB_EXPORT_CLASS(position_controllers::JointTrajectoryController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(velocity_controllers::JointTrajectoryController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(effort_controllers::JointTrajectoryController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(pos_vel_controllers::JointTrajectoryController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(pos_vel_acc_controllers::JointTrajectoryController, controller_interface::ControllerBase)
