// Test controllers of the controller_manager re-implementation.
#pragma once

#include <controller_manager_tests/command_test_controller.h>

namespace controller_manager_tests
{
/// Writes `velocity` (default 0.5) to `joints` through the VelocityJointInterface.
class VelocityTestController : public CommandTestController<hardware_interface::VelocityJointInterface>
{
public:
  VelocityTestController() : CommandTestController("velocity", 0.5) {}
};

}  // namespace controller_manager_tests
