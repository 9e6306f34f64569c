// Test controller plugins of the controller_manager re-implementation.
#include <pluginlib/class_list_macros.hpp>

#include <controller_manager_tests/effort_test_controller.h>
#include <controller_manager_tests/imu_test_controller.h>
#include <controller_manager_tests/multi_test_controller.h>
#include <controller_manager_tests/state_test_controller.h>
#include <controller_manager_tests/velocity_test_controller.h>

PLUGINLIB_EXPORT_CLASS(controller_manager_tests::EffortTestController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(controller_manager_tests::VelocityTestController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(controller_manager_tests::StateTestController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(controller_manager_tests::ImuTestController, controller_interface::ControllerBase)
PLUGINLIB_EXPORT_CLASS(controller_manager_tests::MultiTestController, controller_interface::ControllerBase)
