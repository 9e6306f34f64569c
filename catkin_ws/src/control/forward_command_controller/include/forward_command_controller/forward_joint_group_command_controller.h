// Re-implementation of forward_command_controller/forward_joint_group_command_controller.h
// (ros_controllers 0.21): forwards std_msgs/Float64MultiArray from `<controller>/command` to
// the commands of the joints listed in `joints`.
#pragma once

#include <string>
#include <vector>

#include <controller_interface/controller.h>
#include <forward_command_controller/joint_setup.h>
#include <hardware_interface/joint_command_interface.h>
#include <realtime_tools/realtime_buffer.h>
#include <ros/node_handle.h>
#include <std_msgs/Float64MultiArray.h>

namespace forward_command_controller
{

/**
 * Parameters: `joints` (required, non-empty list). Subscribes `command`
 * (std_msgs/Float64MultiArray); a command whose size differs from the number of joints, or that
 * holds a NaN/inf, is refused with an ERROR. starting(): zeros, or the current positions for
 * PositionJointInterface.
 */
template <class T>
class ForwardJointGroupCommandController : public controller_interface::Controller<T>
{
public:
  ForwardJointGroupCommandController() = default;
  ~ForwardJointGroupCommandController() override { sub_command_.shutdown(); }

  bool init(T* hw, ros::NodeHandle& n) override
  {
    if (!internal::getJointNames(n, joint_names_))
      return false;
    n_joints_ = joint_names_.size();
    if (!internal::getJointHandles(hw, joint_names_, joints_))
      return false;
    commands_buffer_.writeFromNonRT(std::vector<double>(n_joints_, 0.0));
    sub_command_ =
        n.subscribe<std_msgs::Float64MultiArray>("command", 1, &ForwardJointGroupCommandController::commandCB, this);
    return true;
  }

  void starting(const ros::Time& time) override;

  void update(const ros::Time& /*time*/, const ros::Duration& /*period*/) override
  {
    const std::vector<double>& commands = *commands_buffer_.readFromRT();
    for (unsigned int i = 0; i < n_joints_; ++i)
      joints_[i].setCommand(commands[i]);
  }

  std::vector<std::string> joint_names_;
  std::vector<hardware_interface::JointHandle> joints_;
  realtime_tools::RealtimeBuffer<std::vector<double>> commands_buffer_;
  unsigned int n_joints_ = 0;

private:
  ros::Subscriber sub_command_;

  void commandCB(const std_msgs::Float64MultiArrayConstPtr& msg)
  {
    std::string error;
    if (!internal::checkGroupCommand(msg->data, n_joints_, error))
    {
      ROS_ERROR_STREAM_THROTTLE(1.0, error);
      return;
    }
    commands_buffer_.writeFromNonRT(msg->data);
  }
};

template <class T>
void ForwardJointGroupCommandController<T>::starting(const ros::Time& /*time*/)
{
  commands_buffer_.writeFromNonRT(std::vector<double>(n_joints_, 0.0));
}

/// Position group forwarders start by holding the current positions.
template <>
inline void ForwardJointGroupCommandController<hardware_interface::PositionJointInterface>::starting(
    const ros::Time& /*time*/)
{
  std::vector<double> positions(n_joints_);
  for (unsigned int i = 0; i < n_joints_; ++i)
    positions[i] = joints_[i].getPosition();
  commands_buffer_.writeFromNonRT(positions);
}

}  // namespace forward_command_controller
