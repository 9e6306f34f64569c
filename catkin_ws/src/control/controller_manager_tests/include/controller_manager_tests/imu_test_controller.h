// Test controllers of the controller_manager re-implementation.
#pragma once

#include <controller_interface/controller.h>
#include <hardware_interface/imu_sensor_interface.h>

namespace controller_manager_tests
{
/// Needs an ImuSensorInterface (the dummy robot has none: its init must be refused).
class ImuTestController : public controller_interface::Controller<hardware_interface::ImuSensorInterface>
{
public:
  void update(const ros::Time& /*time*/, const ros::Duration& /*period*/) override {}
};

}  // namespace controller_manager_tests
