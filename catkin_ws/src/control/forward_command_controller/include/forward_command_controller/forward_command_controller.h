// Re-implementation of forward_command_controller/forward_command_controller.h (ros_controllers
// 0.21): forwards std_msgs/Float64 from `<controller>/command` to one joint's command.
#pragma once

#include <cmath>
#include <string>

#include <controller_interface/controller.h>
#include <forward_command_controller/joint_setup.h>
#include <hardware_interface/joint_command_interface.h>
#include <realtime_tools/realtime_buffer.h>
#include <ros/node_handle.h>
#include <std_msgs/Float64.h>

namespace forward_command_controller
{

/**
 * Parameters: `joint` (required). Subscribes `command` (std_msgs/Float64). NaN/inf commands are
 * dropped with a throttled warning. starting(): 0 for effort/velocity interfaces, the joint's
 * current position for PositionJointInterface (see the specialisation below).
 */
template <class T>
class ForwardCommandController : public controller_interface::Controller<T>
{
public:
  ForwardCommandController() : command_buffer_(0.0) {}
  ~ForwardCommandController() override { sub_command_.shutdown(); }

  bool init(T* hw, ros::NodeHandle& n) override
  {
    std::string joint_name;
    if (!internal::getJointName(n, joint_name) || !internal::getJointHandle(hw, joint_name, n, joint_))
      return false;
    namespace_ = n.getNamespace();
    sub_command_ = n.subscribe<std_msgs::Float64>("command", 1, &ForwardCommandController::commandCB, this);
    return true;
  }

  void starting(const ros::Time& time) override;

  void update(const ros::Time& /*time*/, const ros::Duration& /*period*/) override
  {
    joint_.setCommand(*command_buffer_.readFromRT());
  }

  hardware_interface::JointHandle joint_;
  realtime_tools::RealtimeBuffer<double> command_buffer_;

private:
  ros::Subscriber sub_command_;
  std::string namespace_;

  void commandCB(const std_msgs::Float64ConstPtr& msg)
  {
    if (!std::isfinite(msg->data))
    {
      ROS_WARN_THROTTLE(1.0, "%s: ignoring a non-finite command (%f)", namespace_.c_str(), msg->data);
      return;
    }
    command_buffer_.writeFromNonRT(msg->data);
  }
};

template <class T>
void ForwardCommandController<T>::starting(const ros::Time& /*time*/)
{
  command_buffer_.writeFromNonRT(0.0);
}

/// Position forwarders start by holding the current position.
template <>
inline void ForwardCommandController<hardware_interface::PositionJointInterface>::starting(const ros::Time& /*time*/)
{
  command_buffer_.writeFromNonRT(joint_.getPosition());
}

}  // namespace forward_command_controller
