#include <pluginlib/class_list_macros.hpp>
#include <velocity_controllers/joint_group_velocity_controller.h>
#include <velocity_controllers/joint_velocity_controller.h>

PLUGINLIB_EXPORT_CLASS(velocity_controllers::JointVelocityController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(velocity_controllers::JointGroupVelocityController, controller_interface::ControllerBase)
