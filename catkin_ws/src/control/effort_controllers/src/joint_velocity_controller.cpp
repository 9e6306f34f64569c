#include <effort_controllers/joint_velocity_controller.h>

#include <cmath>

#include <forward_command_controller/joint_setup.h>
#include <forward_command_controller/pid_state.h>
#include <pluginlib/class_list_macros.hpp>

namespace effort_controllers
{

JointVelocityController::JointVelocityController() : command_buffer_(0.0) {}

JointVelocityController::~JointVelocityController() { sub_command_.shutdown(); }

bool JointVelocityController::init(hardware_interface::EffortJointInterface* robot, const std::string& joint_name,
                                   const control_toolbox::Pid& pid)
{
  pid_controller_ = pid;
  joint_ = robot->getHandle(joint_name);
  return true;
}

bool JointVelocityController::init(hardware_interface::EffortJointInterface* robot, ros::NodeHandle& n)
{
  namespace_ = n.getNamespace();
  std::string joint_name;
  if (!forward_command_controller::internal::getJointName(n, joint_name))
    return false;
  if (!pid_controller_.init(ros::NodeHandle(n, "pid")))
    return false;

  controller_state_publisher_ =
      std::make_unique<realtime_tools::RealtimePublisher<control_msgs::JointControllerState>>(n, "state", 1);
  sub_command_ = n.subscribe<std_msgs::Float64>("command", 1, &JointVelocityController::setCommandCB, this);

  return forward_command_controller::internal::getJointHandle(robot, joint_name, n, joint_);
}

void JointVelocityController::setGains(const double& p, const double& i, const double& d, const double& i_max,
                                       const double& i_min, const bool& antiwindup)
{
  pid_controller_.setGains(p, i, d, i_max, i_min, antiwindup);
}

void JointVelocityController::getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup)
{
  pid_controller_.getGains(p, i, d, i_max, i_min, antiwindup);
}

void JointVelocityController::getGains(double& p, double& i, double& d, double& i_max, double& i_min)
{
  bool dummy = false;
  pid_controller_.getGains(p, i, d, i_max, i_min, dummy);
}

void JointVelocityController::printDebug() { pid_controller_.printValues(); }

std::string JointVelocityController::getJointName() { return joint_.getName(); }

void JointVelocityController::setCommand(double cmd)
{
  command_ = cmd;
  command_buffer_.writeFromNonRT(cmd);
}

void JointVelocityController::getCommand(double& cmd) { cmd = *command_buffer_.readFromNonRT(); }

void JointVelocityController::starting(const ros::Time& /*time*/)
{
  command_ = 0.0;
  command_buffer_.initRT(0.0);
  pid_controller_.reset();
}

void JointVelocityController::update(const ros::Time& time, const ros::Duration& period)
{
  const double command = *command_buffer_.readFromRT();
  const double error = command - joint_.getVelocity();
  const double commanded_effort = pid_controller_.computeCommand(error, period);
  joint_.setCommand(commanded_effort);

  if (loop_count_ % 10 == 0 && controller_state_publisher_ && controller_state_publisher_->trylock())
  {
    forward_command_controller::internal::fillPidState(controller_state_publisher_->msg_, time, command,
                                                       joint_.getVelocity(), error, period, commanded_effort,
                                                       pid_controller_);
    controller_state_publisher_->unlockAndPublish();
  }
  ++loop_count_;
}

void JointVelocityController::setCommandCB(const std_msgs::Float64ConstPtr& msg)
{
  if (!std::isfinite(msg->data))
  {
    ROS_WARN_THROTTLE(1.0, "%s: ignoring a non-finite velocity command (%f)", namespace_.c_str(), msg->data);
    return;
  }
  setCommand(msg->data);
}

}  // namespace effort_controllers

PLUGINLIB_EXPORT_CLASS(effort_controllers::JointVelocityController, controller_interface::ControllerBase)
