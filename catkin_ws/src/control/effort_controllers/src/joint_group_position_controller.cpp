#include <effort_controllers/joint_group_position_controller.h>

#include <cmath>

#include <forward_command_controller/joint_setup.h>
#include <forward_command_controller/urdf_joint.h>
#include <pluginlib/class_list_macros.hpp>

namespace effort_controllers
{
namespace internal = forward_command_controller::internal;

JointGroupPositionController::JointGroupPositionController() = default;

JointGroupPositionController::~JointGroupPositionController() { sub_command_.shutdown(); }

bool JointGroupPositionController::init(hardware_interface::EffortJointInterface* robot, ros::NodeHandle& n)
{
  if (!internal::getJointNames(n, joint_names_))
    return false;
  n_joints_ = joint_names_.size();

  urdf::Model urdf;
  if (!urdf.initParamWithNodeHandle("robot_description", n))
  {
    ROS_ERROR("Failed to parse urdf file");
    return false;
  }

  joints_.clear();
  joint_urdfs_.clear();
  pid_controllers_.resize(n_joints_);
  for (unsigned int i = 0; i < n_joints_; ++i)
  {
    if (!internal::appendJointHandle(robot, joint_names_[i], joints_))
      return false;

    ros::NodeHandle pid_nh(n, std::string("gains/") + joint_names_[i]);
    if (!pid_controllers_[i].init(pid_nh))
      return false;

    urdf::JointConstSharedPtr joint_urdf = internal::getUrdfJoint(urdf, joint_names_[i], "");
    if (!joint_urdf)
      return false;
    joint_urdfs_.push_back(joint_urdf);
  }

  commands_buffer_.writeFromNonRT(std::vector<double>(n_joints_, 0.0));
  sub_command_ = n.subscribe<std_msgs::Float64MultiArray>("command", 1, &JointGroupPositionController::commandCB, this);
  return true;
}

void JointGroupPositionController::starting(const ros::Time& /*time*/)
{
  std::vector<double> commands(n_joints_);
  for (unsigned int i = 0; i < n_joints_; ++i)
  {
    commands[i] = joints_[i].getPosition();
    enforceJointLimits(commands[i], i);
    pid_controllers_[i].reset();
  }
  commands_buffer_.initRT(commands);
}

void JointGroupPositionController::update(const ros::Time& /*time*/, const ros::Duration& period)
{
  const std::vector<double>& commands = *commands_buffer_.readFromRT();
  for (unsigned int i = 0; i < n_joints_; ++i)
  {
    double command_position = commands[i];
    enforceJointLimits(command_position, i);
    const double current_position = joints_[i].getPosition();
    const double error = internal::positionError(joint_urdfs_[i], current_position, command_position);
    joints_[i].setCommand(pid_controllers_[i].computeCommand(error, period));
  }
}

void JointGroupPositionController::commandCB(const std_msgs::Float64MultiArrayConstPtr& msg)
{
  std::string error;
  if (!internal::checkGroupCommand(msg->data, n_joints_, error))
  {
    ROS_ERROR_STREAM_THROTTLE(1.0, error);
    return;
  }
  commands_buffer_.writeFromNonRT(msg->data);
}

void JointGroupPositionController::enforceJointLimits(double& command, unsigned int index)
{
  internal::enforceJointLimits(joint_urdfs_[index], command);
}

}  // namespace effort_controllers

PLUGINLIB_EXPORT_CLASS(effort_controllers::JointGroupPositionController, controller_interface::ControllerBase)
