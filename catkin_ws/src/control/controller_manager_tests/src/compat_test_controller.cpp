// Exported with the ROS 1 header name (pluginlib_compat, found through controller_interface):
// this library must load through the controller manager exactly like one using the .hpp.
#include <pluginlib/class_list_macros.h>

#include <controller_manager_tests/compat_test_controller.h>

PLUGINLIB_EXPORT_CLASS(controller_manager_tests::CompatTestController, controller_interface::ControllerBase)
