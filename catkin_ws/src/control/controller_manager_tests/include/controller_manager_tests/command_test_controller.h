// Test controllers of the controller_manager re-implementation.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <ros/ros.h>

#include <controller_interface/controller.h>
#include <hardware_interface/joint_command_interface.h>

namespace controller_manager_tests
{
/**
 * \brief Writes a constant command to its joints (claiming them through \p Interface).
 *
 * Parameters: `joints` (list of names; default: every joint of the interface), `<param_name>`
 * (the command value, default \p default_value).
 */
template <class Interface>
class CommandTestController : public controller_interface::Controller<Interface>
{
public:
  CommandTestController(const std::string& param_name, double default_value)
    : param_name_(param_name), value_(default_value)
  {
  }

  bool init(Interface* hw, ros::NodeHandle& nh) override
  {
    std::vector<std::string> joints = hw->getNames();
    if (nh.hasParam("joints") && !nh.getParam("joints", joints))
    {
      ROS_ERROR_STREAM("Parameter 'joints' of " << nh.getNamespace() << " must be a list of joint names");
      return false;
    }
    nh.param(param_name_, value_, value_);
    const std::vector<std::string> known = hw->getNames();
    for (const std::string& joint : joints)
    {
      if (std::find(known.begin(), known.end(), joint) == known.end())
      {
        ROS_ERROR_STREAM("Controller " << nh.getNamespace() << ": joint '" << joint << "' not found");
        return false;
      }
      handles_.push_back(hw->getHandle(joint));
    }
    return true;
  }

  void starting(const ros::Time& /*time*/) override { ++starts_; }
  void stopping(const ros::Time& /*time*/) override { ++stops_; }

  void update(const ros::Time& /*time*/, const ros::Duration& /*period*/) override
  {
    ++updates_;
    for (hardware_interface::JointHandle& h : handles_)
      h.setCommand(value_);
  }

  int starts_ = 0, stops_ = 0, updates_ = 0;

private:
  std::string param_name_;
  double value_;
  std::vector<hardware_interface::JointHandle> handles_;
};

}  // namespace controller_manager_tests
