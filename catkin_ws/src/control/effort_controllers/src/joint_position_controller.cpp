#include <effort_controllers/joint_position_controller.h>

#include <cmath>

#include <angles/angles.h>
#include <hardware_interface/hardware_interface_exception.h>
#include <pluginlib/class_list_macros.hpp>

namespace effort_controllers
{

JointPositionController::JointPositionController() = default;

JointPositionController::~JointPositionController() { sub_command_.shutdown(); }

bool JointPositionController::init(hardware_interface::EffortJointInterface* robot, ros::NodeHandle& n)
{
  namespace_ = n.getNamespace();
  std::string joint_name;
  if (!n.getParam("joint", joint_name))
  {
    ROS_ERROR("No joint given (namespace: %s)", n.getNamespace().c_str());
    return false;
  }

  if (!pid_controller_.init(ros::NodeHandle(n, "pid")))
    return false;

  controller_state_publisher_ =
      std::make_unique<realtime_tools::RealtimePublisher<control_msgs::JointControllerState>>(n, "state", 1);
  sub_command_ = n.subscribe<std_msgs::Float64>("command", 1, &JointPositionController::setCommandCB, this);

  try
  {
    joint_ = robot->getHandle(joint_name);
  }
  catch (const hardware_interface::HardwareInterfaceException& e)
  {
    ROS_ERROR("Could not get joint '%s' (namespace: %s): %s", joint_name.c_str(), n.getNamespace().c_str(), e.what());
    return false;
  }

  urdf::Model urdf;
  if (!urdf.initParamWithNodeHandle("robot_description", n))
  {
    ROS_ERROR("Failed to parse urdf file");
    return false;
  }
  joint_urdf_ = urdf.getJoint(joint_name);
  if (!joint_urdf_)
  {
    ROS_ERROR("Could not find joint '%s' in urdf", joint_name.c_str());
    return false;
  }
  if ((joint_urdf_->type == urdf::Joint::REVOLUTE || joint_urdf_->type == urdf::Joint::PRISMATIC) &&
      !joint_urdf_->limits)
  {
    ROS_ERROR("Joint '%s' has no <limit> in the urdf (namespace: %s)", joint_name.c_str(), n.getNamespace().c_str());
    return false;
  }
  return true;
}

bool JointPositionController::init(hardware_interface::EffortJointInterface* robot, const std::string& joint_name,
                                   const control_toolbox::Pid& pid)
{
  pid_controller_ = pid;
  joint_ = robot->getHandle(joint_name);
  return true;
}

void JointPositionController::setGains(const double& p, const double& i, const double& d, const double& i_max,
                                       const double& i_min, const bool& antiwindup)
{
  pid_controller_.setGains(p, i, d, i_max, i_min, antiwindup);
}

void JointPositionController::getGains(double& p, double& i, double& d, double& i_max, double& i_min,
                                       bool& antiwindup)
{
  pid_controller_.getGains(p, i, d, i_max, i_min, antiwindup);
}

void JointPositionController::getGains(double& p, double& i, double& d, double& i_max, double& i_min)
{
  bool dummy = false;
  pid_controller_.getGains(p, i, d, i_max, i_min, dummy);
}

void JointPositionController::printDebug() { pid_controller_.printValues(); }

std::string JointPositionController::getJointName() { return joint_.getName(); }

double JointPositionController::getPosition() { return joint_.getPosition(); }

void JointPositionController::setCommand(double pos_command)
{
  command_struct_.position_ = pos_command;
  command_struct_.has_velocity_ = false;
  command_.writeFromNonRT(command_struct_);
}

void JointPositionController::setCommand(double pos_command, double vel_command)
{
  command_struct_.position_ = pos_command;
  command_struct_.velocity_ = vel_command;
  command_struct_.has_velocity_ = true;
  command_.writeFromNonRT(command_struct_);
}

void JointPositionController::starting(const ros::Time& /*time*/)
{
  double pos_command = joint_.getPosition();
  enforceJointLimits(pos_command);
  command_struct_.position_ = pos_command;
  command_struct_.has_velocity_ = false;
  command_.initRT(command_struct_);
  pid_controller_.reset();
}

void JointPositionController::update(const ros::Time& time, const ros::Duration& period)
{
  command_struct_ = *command_.readFromRT();
  double command_position = command_struct_.position_;
  const double current_position = joint_.getPosition();

  enforceJointLimits(command_position);

  double error = 0.0;
  if (!joint_urdf_ || joint_urdf_->type == urdf::Joint::PRISMATIC)
    error = command_position - current_position;
  else if (joint_urdf_->type == urdf::Joint::REVOLUTE)
    angles::shortest_angular_distance_with_large_limits(current_position, command_position, joint_urdf_->limits->lower, joint_urdf_->limits->upper, error);
  else if (joint_urdf_->type == urdf::Joint::CONTINUOUS)
    error = angles::shortest_angular_distance(current_position, command_position);
  else
    error = command_position - current_position;

  double commanded_effort = 0.0;
  if (command_struct_.has_velocity_)
  {
    const double vel_error = command_struct_.velocity_ - joint_.getVelocity();
    commanded_effort = pid_controller_.computeCommand(error, vel_error, period);
  }
  else
  {
    commanded_effort = pid_controller_.computeCommand(error, period);
  }
  joint_.setCommand(commanded_effort);

  if (loop_count_ % 10 == 0 && controller_state_publisher_ && controller_state_publisher_->trylock())
  {
    control_msgs::JointControllerState& msg = controller_state_publisher_->msg_;
    msg.header.stamp = time;
    msg.set_point = command_position;
    msg.process_value = current_position;
    msg.process_value_dot = joint_.getVelocity();
    msg.error = error;
    msg.time_step = period.toSec();
    msg.command = commanded_effort;
    double dummy = 0.0;
    bool antiwindup = false;
    getGains(msg.p, msg.i, msg.d, msg.i_clamp, dummy, antiwindup);
    msg.antiwindup = antiwindup;
    controller_state_publisher_->unlockAndPublish();
  }
  ++loop_count_;
}

void JointPositionController::setCommandCB(const std_msgs::Float64ConstPtr& msg)
{
  if (!std::isfinite(msg->data))
  {
    ROS_WARN_THROTTLE(1.0, "%s: ignoring a non-finite position command (%f)", namespace_.c_str(), msg->data);
    return;
  }
  setCommand(msg->data);
}

void JointPositionController::enforceJointLimits(double& command)
{
  if (joint_urdf_ && joint_urdf_->limits &&
      (joint_urdf_->type == urdf::Joint::REVOLUTE || joint_urdf_->type == urdf::Joint::PRISMATIC))
  {
    if (command > joint_urdf_->limits->upper)
      command = joint_urdf_->limits->upper;
    else if (command < joint_urdf_->limits->lower)
      command = joint_urdf_->limits->lower;
  }
}

}  // namespace effort_controllers

PLUGINLIB_EXPORT_CLASS(effort_controllers::JointPositionController, controller_interface::ControllerBase)
