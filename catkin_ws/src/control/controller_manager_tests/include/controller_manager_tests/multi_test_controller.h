// Test controllers of the controller_manager re-implementation.
#pragma once

#include <string>
#include <vector>

#include <ros/ros.h>

#include <controller_interface/multi_interface_controller.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>

namespace controller_manager_tests
{
/// Velocity commands to `velocity_joints` and position commands to `position_joints`.
class MultiTestController
  : public controller_interface::MultiInterfaceController<hardware_interface::VelocityJointInterface,
                                                          hardware_interface::PositionJointInterface>
{
public:
  bool init(hardware_interface::RobotHW* hw, ros::NodeHandle& nh) override
  {
    std::vector<std::string> vel_joints, pos_joints;
    nh.getParam("velocity_joints", vel_joints);
    nh.getParam("position_joints", pos_joints);
    try
    {
      for (const std::string& j : vel_joints)
        vel_.push_back(hw->get<hardware_interface::VelocityJointInterface>()->getHandle(j));
      for (const std::string& j : pos_joints)
        pos_.push_back(hw->get<hardware_interface::PositionJointInterface>()->getHandle(j));
    }
    catch (const hardware_interface::HardwareInterfaceException& e)
    {
      ROS_ERROR_STREAM("MultiTestController: " << e.what());
      return false;
    }
    return true;
  }

  void starting(const ros::Time& /*time*/) override
  {
    for (auto& h : pos_)
      h.setCommand(h.getPosition());
  }

  void update(const ros::Time& /*time*/, const ros::Duration& /*period*/) override
  {
    for (auto& h : vel_)
      h.setCommand(0.25);
  }

private:
  std::vector<hardware_interface::JointHandle> vel_, pos_;
};

}  // namespace controller_manager_tests
