#include <effort_controllers/joint_group_position_controller.h>

#include <cmath>

#include <control_toolbox/angles.h>
#include <hardware_interface/hardware_interface_exception.h>
#include <pluginlib/class_list_macros.hpp>

namespace effort_controllers
{

JointGroupPositionController::JointGroupPositionController() = default;

JointGroupPositionController::~JointGroupPositionController() { sub_command_.shutdown(); }

bool JointGroupPositionController::init(hardware_interface::EffortJointInterface* robot, ros::NodeHandle& n)
{
  const std::string param_name = "joints";
  if (!n.getParam(param_name, joint_names_))
  {
    ROS_ERROR_STREAM("Failed to getParam '" << param_name << "' (namespace: " << n.getNamespace() << ").");
    return false;
  }
  n_joints_ = joint_names_.size();
  if (n_joints_ == 0)
  {
    ROS_ERROR_STREAM("List of joint names is empty.");
    return false;
  }

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
    try
    {
      joints_.push_back(robot->getHandle(joint_names_[i]));
    }
    catch (const hardware_interface::HardwareInterfaceException& e)
    {
      ROS_ERROR_STREAM("Exception thrown: " << e.what());
      return false;
    }

    ros::NodeHandle pid_nh(n, std::string("gains/") + joint_names_[i]);
    if (!pid_controllers_[i].init(pid_nh))
      return false;

    urdf::JointConstSharedPtr joint_urdf = urdf.getJoint(joint_names_[i]);
    if (!joint_urdf)
    {
      ROS_ERROR("Could not find joint '%s' in urdf", joint_names_[i].c_str());
      return false;
    }
    if ((joint_urdf->type == urdf::Joint::REVOLUTE || joint_urdf->type == urdf::Joint::PRISMATIC) &&
        !joint_urdf->limits)
    {
      ROS_ERROR("Joint '%s' has no <limit> in the urdf", joint_names_[i].c_str());
      return false;
    }
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
    const urdf::JointConstSharedPtr& joint_urdf = joint_urdfs_[i];

    double error = 0.0;
    if (joint_urdf->type == urdf::Joint::REVOLUTE)
      error = control_toolbox::angles::revolute_error(current_position, command_position, joint_urdf->limits->lower,
                                                      joint_urdf->limits->upper);
    else if (joint_urdf->type == urdf::Joint::CONTINUOUS)
      error = control_toolbox::angles::shortest_angular_distance(current_position, command_position);
    else
      error = command_position - current_position;

    joints_[i].setCommand(pid_controllers_[i].computeCommand(error, period));
  }
}

void JointGroupPositionController::commandCB(const std_msgs::Float64MultiArrayConstPtr& msg)
{
  if (msg->data.size() != n_joints_)
  {
    ROS_ERROR_STREAM_THROTTLE(1.0, "Dimension of command (" << msg->data.size() << ") does not match number of joints ("
                                              << n_joints_ << ")! Not executing!");
    return;
  }
  for (double value : msg->data)
  {
    if (!std::isfinite(value))
    {
      ROS_ERROR_STREAM_THROTTLE(1.0, "Command holds a non-finite value (" << value << ")! Not executing!");
      return;
    }
  }
  commands_buffer_.writeFromNonRT(msg->data);
}

void JointGroupPositionController::enforceJointLimits(double& command, unsigned int index)
{
  const urdf::JointConstSharedPtr& joint_urdf = joint_urdfs_[index];
  if (joint_urdf->limits && (joint_urdf->type == urdf::Joint::REVOLUTE || joint_urdf->type == urdf::Joint::PRISMATIC))
  {
    if (command > joint_urdf->limits->upper)
      command = joint_urdf->limits->upper;
    else if (command < joint_urdf->limits->lower)
      command = joint_urdf->limits->lower;
  }
}

}  // namespace effort_controllers

PLUGINLIB_EXPORT_CLASS(effort_controllers::JointGroupPositionController, controller_interface::ControllerBase)
