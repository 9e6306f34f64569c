#include <pluginlib/class_list_macros.hpp>
#include <position_controllers/joint_group_position_controller.h>
#include <position_controllers/joint_position_controller.h>

PLUGINLIB_EXPORT_CLASS(position_controllers::JointPositionController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(position_controllers::JointGroupPositionController, controller_interface::ControllerBase)
