#include <velocity_controllers/joint_position_controller.h>

#include <pluginlib/class_list_macros.hpp>

PLUGINLIB_EXPORT_CLASS(velocity_controllers::JointPositionController, controller_interface::ControllerBase)
