// Test controllers of the controller_manager re-implementation.
#pragma once

#include <controller_manager_tests/command_test_controller.h>

namespace controller_manager_tests
{
/// Writes `effort` (default 1.0) to `joints` through the EffortJointInterface.
class EffortTestController : public CommandTestController<hardware_interface::EffortJointInterface>
{
public:
  EffortTestController() : CommandTestController("effort", 1.0) {}
};

}  // namespace controller_manager_tests
