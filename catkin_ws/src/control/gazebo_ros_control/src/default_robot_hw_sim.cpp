#include <gazebo_ros_control/default_robot_hw_sim.h>

#include <limits>

namespace gazebo_ros_control
{

bool DefaultRobotHWSim::initSim(const std::string& robot_namespace, ros::NodeHandle model_nh, BridgeModel* parent_model)
{
  (void)model_nh;
  model_ = parent_model;
  n_dof_ = model_->size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  joint_names_.resize(n_dof_);
  joint_control_methods_.resize(n_dof_);
  joint_position_.assign(n_dof_, 0.0);
  joint_velocity_.assign(n_dof_, 0.0);
  joint_effort_.assign(n_dof_, 0.0);
  // NaN = no command yet: the simulator keeps the joint still until a controller commands it
  joint_effort_command_.assign(n_dof_, nan);
  joint_velocity_command_.assign(n_dof_, nan);
  joint_position_command_.assign(n_dof_, nan);
  last_joint_position_command_.assign(n_dof_, nan);
  saturation_.clear();

  for (std::size_t j = 0; j < n_dof_; ++j)
  {
    const BridgeJoint& joint = model_->joints()[j];
    joint_names_[j] = joint.name;
    joint_control_methods_[j] = joint.interface;
    saturation_.emplace_back(joint);
    ROS_DEBUG_STREAM_NAMED("default_robot_hw_sim", "Loading joint '" << joint.name << "' of type '"
                                                                     << jointInterfaceName(joint.interface) << "'");
    js_interface_.registerHandle(
        hardware_interface::JointStateHandle(joint.name, &joint_position_[j], &joint_velocity_[j], &joint_effort_[j]));
    switch (joint.interface)
    {
      case JointInterface::EFFORT:
        ej_interface_.registerHandle(
            hardware_interface::JointHandle(js_interface_.getHandle(joint.name), &joint_effort_command_[j]));
        break;
      case JointInterface::VELOCITY:
        vj_interface_.registerHandle(
            hardware_interface::JointHandle(js_interface_.getHandle(joint.name), &joint_velocity_command_[j]));
        break;
      case JointInterface::POSITION:
        pj_interface_.registerHandle(
            hardware_interface::JointHandle(js_interface_.getHandle(joint.name), &joint_position_command_[j]));
        break;
      case JointInterface::STATE:
        break;
    }
  }
  registerInterface(&js_interface_);
  registerInterface(&ej_interface_);
  registerInterface(&vj_interface_);
  registerInterface(&pj_interface_);
  ROS_INFO_STREAM_NAMED("default_robot_hw_sim", "DefaultRobotHWSim in namespace '"
                                                    << (robot_namespace.empty() ? "/" : robot_namespace)
                                                    << "': " << n_dof_ << " joint(s)");
  return true;
}

void DefaultRobotHWSim::readSim(ros::Time time, ros::Duration period)
{
  (void)time;
  (void)period;
  for (std::size_t j = 0; j < n_dof_; ++j)
  {
    joint_position_[j] = model_->position(j);
    joint_velocity_[j] = model_->velocity(j);
    joint_effort_[j] = model_->effort(j);
  }
}

void DefaultRobotHWSim::writeSim(ros::Time time, ros::Duration period)
{
  (void)time;
  // e-stop: remember where the positions were when it began
  if (e_stop_active_)
  {
    if (!last_e_stop_active_)
    {
      last_joint_position_command_ = joint_position_;
      last_e_stop_active_ = true;
    }
  }
  else
  {
    last_e_stop_active_ = false;
  }
  const double dt = period.toSec();
  for (std::size_t j = 0; j < n_dof_; ++j)
  {
    double cmd = std::numeric_limits<double>::quiet_NaN();
    switch (joint_control_methods_[j])
    {
      case JointInterface::EFFORT:
        cmd = e_stop_active_ ? 0.0 : joint_effort_command_[j];
        break;
      case JointInterface::VELOCITY:
        cmd = e_stop_active_ ? 0.0 : joint_velocity_command_[j];
        break;
      case JointInterface::POSITION:
        cmd = e_stop_active_ ? last_joint_position_command_[j] : joint_position_command_[j];
        break;
      case JointInterface::STATE:
        continue;
    }
    if (e_stop_active_)
      saturation_[j].reset();
    else
      cmd = enforceAndStore(j, cmd, dt);
    model_->setCommand(j, cmd);
  }
}

double DefaultRobotHWSim::enforceAndStore(std::size_t j, double cmd, double dt)
{
  // as joint_limits_interface's saturation handles: the limited value replaces the command
  cmd = saturation_[j].enforce(cmd, joint_position_[j], joint_velocity_[j], dt);
  switch (joint_control_methods_[j])
  {
    case JointInterface::EFFORT:
      joint_effort_command_[j] = cmd;
      break;
    case JointInterface::VELOCITY:
      joint_velocity_command_[j] = cmd;
      break;
    case JointInterface::POSITION:
      joint_position_command_[j] = cmd;
      break;
    case JointInterface::STATE:
      break;
  }
  return cmd;
}

void DefaultRobotHWSim::eStopActive(const bool active) { e_stop_active_ = active; }

}  // namespace gazebo_ros_control
