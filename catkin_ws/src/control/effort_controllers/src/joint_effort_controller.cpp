#include <effort_controllers/joint_effort_controller.h>
#include <effort_controllers/joint_group_effort_controller.h>
#include <pluginlib/class_list_macros.hpp>

PLUGINLIB_EXPORT_CLASS(effort_controllers::JointEffortController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(effort_controllers::JointGroupEffortController, controller_interface::ControllerBase)
