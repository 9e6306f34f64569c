// PID position controller shared by effort_controllers::JointPositionController (output: joint
// effort) and velocity_controllers::JointPositionController (output: joint velocity), which in
// ros_controllers 0.21 are two copies of the same code. Header-only template: the plugins are
// the subclasses in those packages (they also need angles, control_msgs, control_toolbox and
// urdf, which their CMakeLists find).
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include <angles/angles.h>
#include <control_msgs/JointControllerState.h>
#include <control_toolbox/pid.h>
#include <controller_interface/controller.h>
#include <forward_command_controller/joint_setup.h>
#include <forward_command_controller/pid_state.h>
#include <forward_command_controller/urdf_joint.h>
#include <hardware_interface/joint_command_interface.h>
#include <realtime_tools/realtime_buffer.h>
#include <realtime_tools/realtime_publisher.h>
#include <ros/console.h>
#include <ros/node_handle.h>
#include <std_msgs/Float64.h>
#include <urdf/model.h>

namespace forward_command_controller
{

/**
 * PID from a position set point to the command of one joint of HardwareInterface
 * (EffortJointInterface or VelocityJointInterface).
 *
 * Parameters (controller namespace): `joint` (required), `pid/{p,i,d,i_clamp,...}` (p required),
 * and `robot_description` found upward from the namespace (joint type and limits).
 * Subscribes `command` (std_msgs/Float64, position [rad or m]); publishes `state`
 * (control_msgs/JointControllerState) every 10th update.
 * Error: shortest angle within the limits for revolute joints, shortest angle for continuous
 * joints, difference for prismatic; set points are clamped to the URDF limits.
 */
template <class HardwareInterface>
class JointPositionPidController : public controller_interface::Controller<HardwareInterface>
{
public:
  /// Set point; the velocity set point is used (as the PID's error derivative) when has_velocity_.
  struct Commands
  {
    double position_ = 0.0;
    double velocity_ = 0.0;
    bool has_velocity_ = false;
  };

  JointPositionPidController() = default;
  ~JointPositionPidController() override { sub_command_.shutdown(); }

  bool init(HardwareInterface* robot, const std::string& joint_name, const control_toolbox::Pid& pid);
  bool init(HardwareInterface* robot, ros::NodeHandle& n) override;

  /// Position set point [rad or m] (non-realtime).
  void setCommand(double pos_command);
  /// Position [rad or m] and velocity [rad/s or m/s] set points (non-realtime).
  void setCommand(double pos_command, double vel_command);

  void starting(const ros::Time& time) override;
  void update(const ros::Time& time, const ros::Duration& period) override;

  void getGains(double& p, double& i, double& d, double& i_max, double& i_min)
  {
    bool dummy = false;
    pid_controller_.getGains(p, i, d, i_max, i_min, dummy);
  }
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup)
  {
    pid_controller_.getGains(p, i, d, i_max, i_min, antiwindup);
  }
  void setGains(const double& p, const double& i, const double& d, const double& i_max, const double& i_min,
                const bool& antiwindup = false)
  {
    pid_controller_.setGains(p, i, d, i_max, i_min, antiwindup);
  }
  void printDebug() { pid_controller_.printValues(); }
  std::string getJointName() { return joint_.getName(); }
  double getPosition() { return joint_.getPosition(); }

  hardware_interface::JointHandle joint_;
  urdf::JointConstSharedPtr joint_urdf_;
  realtime_tools::RealtimeBuffer<Commands> command_;
  Commands command_struct_;

private:
  int loop_count_ = 0;
  control_toolbox::Pid pid_controller_;
  std::unique_ptr<realtime_tools::RealtimePublisher<control_msgs::JointControllerState>> controller_state_publisher_;
  ros::Subscriber sub_command_;
  std::string namespace_;

  void setCommandCB(const std_msgs::Float64ConstPtr& msg);
  void enforceJointLimits(double& command);
};

template <class HardwareInterface>
bool JointPositionPidController<HardwareInterface>::init(HardwareInterface* robot, ros::NodeHandle& n)
{
  namespace_ = n.getNamespace();
  std::string joint_name;
  if (!internal::getJointName(n, joint_name))
    return false;

  if (!pid_controller_.init(ros::NodeHandle(n, "pid")))
    return false;

  controller_state_publisher_ =
      std::make_unique<realtime_tools::RealtimePublisher<control_msgs::JointControllerState>>(n, "state", 1);
  sub_command_ = n.subscribe<std_msgs::Float64>("command", 1, &JointPositionPidController::setCommandCB, this);

  if (!internal::getJointHandle(robot, joint_name, n, joint_))
    return false;

  urdf::Model urdf;
  if (!urdf.initParamWithNodeHandle("robot_description", n))
  {
    ROS_ERROR("Failed to parse urdf file");
    return false;
  }
  joint_urdf_ = internal::getUrdfJoint(urdf, joint_name, " (namespace: " + n.getNamespace() + ")");
  return static_cast<bool>(joint_urdf_);
}

template <class HardwareInterface>
bool JointPositionPidController<HardwareInterface>::init(HardwareInterface* robot, const std::string& joint_name,
                                                         const control_toolbox::Pid& pid)
{
  pid_controller_ = pid;
  joint_ = robot->getHandle(joint_name);
  return true;
}

template <class HardwareInterface>
void JointPositionPidController<HardwareInterface>::setCommand(double pos_command)
{
  command_struct_.position_ = pos_command;
  command_struct_.has_velocity_ = false;
  command_.writeFromNonRT(command_struct_);
}

template <class HardwareInterface>
void JointPositionPidController<HardwareInterface>::setCommand(double pos_command, double vel_command)
{
  command_struct_.position_ = pos_command;
  command_struct_.velocity_ = vel_command;
  command_struct_.has_velocity_ = true;
  command_.writeFromNonRT(command_struct_);
}

template <class HardwareInterface>
void JointPositionPidController<HardwareInterface>::starting(const ros::Time& /*time*/)
{
  double pos_command = joint_.getPosition();
  enforceJointLimits(pos_command);
  command_struct_.position_ = pos_command;
  command_struct_.has_velocity_ = false;
  command_.initRT(command_struct_);
  pid_controller_.reset();
}

template <class HardwareInterface>
void JointPositionPidController<HardwareInterface>::update(const ros::Time& time, const ros::Duration& period)
{
  command_struct_ = *command_.readFromRT();
  double command_position = command_struct_.position_;
  const double current_position = joint_.getPosition();

  enforceJointLimits(command_position);

  const double error = internal::positionError(joint_urdf_, current_position, command_position);

  // effort or velocity, depending on HardwareInterface
  double commanded = 0.0;
  if (command_struct_.has_velocity_)
  {
    const double vel_error = command_struct_.velocity_ - joint_.getVelocity();
    commanded = pid_controller_.computeCommand(error, vel_error, period);
  }
  else
  {
    commanded = pid_controller_.computeCommand(error, period);
  }
  joint_.setCommand(commanded);

  if (loop_count_ % 10 == 0 && controller_state_publisher_ && controller_state_publisher_->trylock())
  {
    control_msgs::JointControllerState& msg = controller_state_publisher_->msg_;
    internal::fillPidState(msg, time, command_position, current_position, error, period, commanded, pid_controller_);
    msg.process_value_dot = joint_.getVelocity();
    controller_state_publisher_->unlockAndPublish();
  }
  ++loop_count_;
}

template <class HardwareInterface>
void JointPositionPidController<HardwareInterface>::setCommandCB(const std_msgs::Float64ConstPtr& msg)
{
  if (!std::isfinite(msg->data))
  {
    ROS_WARN_THROTTLE(1.0, "%s: ignoring a non-finite position command (%f)", namespace_.c_str(), msg->data);
    return;
  }
  setCommand(msg->data);
}

template <class HardwareInterface>
void JointPositionPidController<HardwareInterface>::enforceJointLimits(double& command)
{
  internal::enforceJointLimits(joint_urdf_, command);
}

}  // namespace forward_command_controller
