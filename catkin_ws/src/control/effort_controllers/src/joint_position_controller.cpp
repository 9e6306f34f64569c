#include <effort_controllers/joint_position_controller.h>

#include <pluginlib/class_list_macros.hpp>

PLUGINLIB_EXPORT_CLASS(effort_controllers::JointPositionController, controller_interface::ControllerBase)
