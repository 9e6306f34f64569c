// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <control_toolbox/pid.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/posvel_command_interface.h>
#include <hardware_interface/posvelacc_command_interface.h>
#include <ros/node_handle.h>
#include <ros/time.h>

/**
 * \brief Turns the desired state and the state error of the joints into commands of
 * \p HardwareInterface. Specialised for position, velocity, effort, pos-vel and pos-vel-acc
 * interfaces; other interfaces get a compile error naming this template.
 */
template <class HardwareInterface, class State>
class HardwareInterfaceAdapter
{
public:
  bool init(std::vector<typename HardwareInterface::ResourceHandleType>& /*joint_handles*/,
            ros::NodeHandle& /*controller_nh*/)
  {
    static_assert(sizeof(HardwareInterface) == 0, "No HardwareInterfaceAdapter for this hardware interface");
    return false;
  }
  void starting(const ros::Time& /*time*/) {}
  void stopping(const ros::Time& /*time*/) {}
  void updateCommand(const ros::Time&, const ros::Duration&, const State&, const State&) {}
};

/// Position interface: the desired position is the command; starting commands the current position.
template <class State>
class HardwareInterfaceAdapter<hardware_interface::PositionJointInterface, State>
{
public:
  bool init(std::vector<hardware_interface::JointHandle>& joint_handles, ros::NodeHandle& /*controller_nh*/)
  {
    joint_handles_ptr_ = &joint_handles;
    return true;
  }

  void starting(const ros::Time& /*time*/)
  {
    if (!joint_handles_ptr_)
      return;
    for (auto& h : *joint_handles_ptr_)
      h.setCommand(h.getPosition());
  }

  void stopping(const ros::Time& /*time*/) {}

  void updateCommand(const ros::Time& /*time*/, const ros::Duration& /*period*/, const State& desired_state,
                     const State& /*state_error*/)
  {
    std::vector<hardware_interface::JointHandle>& handles = *joint_handles_ptr_;
    for (unsigned int i = 0; i < handles.size(); ++i)
      handles[i].setCommand(desired_state.position[i]);
  }

private:
  std::vector<hardware_interface::JointHandle>* joint_handles_ptr_ = nullptr;
};

/**
 * \brief Velocity or effort interface: a PID per joint on the position error (gains from
 * <controller>/gains/<joint>: p, i, d, i_clamp, ...). The velocity adapter adds
 * velocity_ff/<joint> (default 0) times the desired velocity.
 */
template <class State, bool VelocityFeedForward>
class ClosedLoopHardwareInterfaceAdapter
{
public:
  bool init(std::vector<hardware_interface::JointHandle>& joint_handles, ros::NodeHandle& controller_nh)
  {
    joint_handles_ptr_ = &joint_handles;
    const unsigned int n = joint_handles.size();
    pids_.resize(n);
    velocity_ff_.assign(n, 0.0);
    for (unsigned int i = 0; i < n; ++i)
    {
      const std::string& name = joint_handles[i].getName();
      ros::NodeHandle joint_nh(controller_nh, std::string("gains/") + name);
      pids_[i].reset(new control_toolbox::Pid());
      if (!pids_[i]->init(joint_nh))
      {
        ROS_WARN_STREAM("Failed to initialize PID gains from ROS parameter server (namespace '"
                        << joint_nh.getNamespace() << "').");
        return false;
      }
      if (VelocityFeedForward)
        controller_nh.param(std::string("velocity_ff/") + name, velocity_ff_[i], 0.0);
    }
    return true;
  }

  void starting(const ros::Time& /*time*/)
  {
    if (!joint_handles_ptr_)
      return;
    for (unsigned int i = 0; i < pids_.size(); ++i)
    {
      pids_[i]->reset();
      (*joint_handles_ptr_)[i].setCommand(0.0);
    }
  }

  void stopping(const ros::Time& /*time*/) {}

  void updateCommand(const ros::Time& /*time*/, const ros::Duration& period, const State& desired_state,
                     const State& state_error)
  {
    std::vector<hardware_interface::JointHandle>& handles = *joint_handles_ptr_;
    for (unsigned int i = 0; i < handles.size(); ++i)
    {
      const double pid = pids_[i]->computeCommand(state_error.position[i], state_error.velocity[i], period);
      const double ff = VelocityFeedForward ? velocity_ff_[i] * desired_state.velocity[i] : 0.0;
      handles[i].setCommand(ff + pid);
    }
  }

private:
  std::vector<std::shared_ptr<control_toolbox::Pid>> pids_;
  std::vector<double> velocity_ff_;
  std::vector<hardware_interface::JointHandle>* joint_handles_ptr_ = nullptr;
};

template <class State>
class HardwareInterfaceAdapter<hardware_interface::VelocityJointInterface, State>
  : public ClosedLoopHardwareInterfaceAdapter<State, true>
{
};

template <class State>
class HardwareInterfaceAdapter<hardware_interface::EffortJointInterface, State>
  : public ClosedLoopHardwareInterfaceAdapter<State, false>
{
};

/// Position + velocity interface: the desired position and velocity are the commands.
template <class State>
class HardwareInterfaceAdapter<hardware_interface::PosVelJointInterface, State>
{
public:
  bool init(std::vector<hardware_interface::PosVelJointHandle>& joint_handles, ros::NodeHandle& /*controller_nh*/)
  {
    joint_handles_ptr_ = &joint_handles;
    return true;
  }

  void starting(const ros::Time& /*time*/)
  {
    if (!joint_handles_ptr_)
      return;
    for (auto& h : *joint_handles_ptr_)
      h.setCommand(h.getPosition(), 0.0);
  }

  void stopping(const ros::Time& /*time*/) {}

  void updateCommand(const ros::Time& /*time*/, const ros::Duration& /*period*/, const State& desired_state,
                     const State& /*state_error*/)
  {
    std::vector<hardware_interface::PosVelJointHandle>& handles = *joint_handles_ptr_;
    for (unsigned int i = 0; i < handles.size(); ++i)
      handles[i].setCommand(desired_state.position[i], desired_state.velocity[i]);
  }

private:
  std::vector<hardware_interface::PosVelJointHandle>* joint_handles_ptr_ = nullptr;
};

/// Position + velocity + acceleration interface: the whole desired state is the command.
template <class State>
class HardwareInterfaceAdapter<hardware_interface::PosVelAccJointInterface, State>
{
public:
  bool init(std::vector<hardware_interface::PosVelAccJointHandle>& joint_handles, ros::NodeHandle& /*controller_nh*/)
  {
    joint_handles_ptr_ = &joint_handles;
    return true;
  }

  void starting(const ros::Time& /*time*/)
  {
    if (!joint_handles_ptr_)
      return;
    for (auto& h : *joint_handles_ptr_)
      h.setCommand(h.getPosition(), 0.0, 0.0);
  }

  void stopping(const ros::Time& /*time*/) {}

  void updateCommand(const ros::Time& /*time*/, const ros::Duration& /*period*/, const State& desired_state,
                     const State& /*state_error*/)
  {
    std::vector<hardware_interface::PosVelAccJointHandle>& handles = *joint_handles_ptr_;
    for (unsigned int i = 0; i < handles.size(); ++i)
      handles[i].setCommand(desired_state.position[i], desired_state.velocity[i], desired_state.acceleration[i]);
  }

private:
  std::vector<hardware_interface::PosVelAccJointHandle>* joint_handles_ptr_ = nullptr;
};
