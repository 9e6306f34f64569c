// Test controllers of the controller_manager re-implementation.
#pragma once

#include <controller_manager_tests/state_test_controller.h>

namespace controller_manager_tests
{
/// A StateTestController exported from its own library through the ROS 1 header
/// <pluginlib/class_list_macros.h> (package pluginlib_compat), to test that header.
class CompatTestController : public StateTestController
{
};

}  // namespace controller_manager_tests
