// Test controllers of the controller_manager re-implementation.
#pragma once

#include <ros/ros.h>

#include <controller_interface/controller.h>
#include <hardware_interface/joint_state_interface.h>

namespace controller_manager_tests
{
/// Reads every joint state (claims nothing); with `fail_init: true` its init fails.
class StateTestController : public controller_interface::Controller<hardware_interface::JointStateInterface>
{
public:
  bool init(hardware_interface::JointStateInterface* hw, ros::NodeHandle& nh) override
  {
    if (nh.param("fail_init", false))
    {
      ROS_ERROR_STREAM("StateTestController " << nh.getNamespace() << ": init fails as configured (fail_init)");
      return false;
    }
    for (const std::string& name : hw->getNames())
      handles_.push_back(hw->getHandle(name));
    return true;
  }

  void update(const ros::Time& /*time*/, const ros::Duration& /*period*/) override
  {
    double sum = 0.0;
    for (const auto& h : handles_)
      sum += h.getPosition();
    last_sum_ = sum;
  }

  double last_sum_ = 0.0;

private:
  std::vector<hardware_interface::JointStateHandle> handles_;
};

}  // namespace controller_manager_tests
