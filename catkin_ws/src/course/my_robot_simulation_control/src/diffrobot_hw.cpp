#include <my_robot_simulation_control/diffrobot_hw.h>

#include <cmath>

namespace my_robot_simulation_control
{

bool DiffRobotHW::init(ros::NodeHandle& root_nh, ros::NodeHandle& robot_hw_nh)
{
  robot_hw_nh.param("joints", joint_names_, std::vector<std::string>{ "wheel_left_joint", "wheel_right_joint" });
  const std::size_t n = joint_names_.size();
  pos_.assign(n, 0.0);
  vel_.assign(n, 0.0);
  eff_.assign(n, 0.0);
  cmd_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    hardware_interface::JointStateHandle state_handle(joint_names_[i], &pos_[i], &vel_[i], &eff_[i]);
    jnt_state_interface_.registerHandle(state_handle);
    jnt_eff_interface_.registerHandle(hardware_interface::JointHandle(state_handle, &cmd_[i]));
  }
  registerInterface(&jnt_state_interface_);
  registerInterface(&jnt_eff_interface_);

  command_pub_ = root_nh.advertise<sensor_msgs::JointState>("ode_sim/joint_commands", 10);
  ros::SubscribeOptions so = ros::SubscribeOptions::create<sensor_msgs::JointState>(
      "ode_sim/joint_states", 10, [this](const sensor_msgs::JointStateConstPtr& m) { stateCallback(m); },
      ros::VoidPtr(), &queue_);
  so.transport_hints = ros::TransportHints().tcpNoDelay();
  state_sub_ = root_nh.subscribe(so);
  ROS_INFO_STREAM("DiffRobotHW: " << n << " effort joints in " << root_nh.getNamespace());
  return true;
}

void DiffRobotHW::stateCallback(const sensor_msgs::JointStateConstPtr& msg)
{
  state_ = msg;
  fresh_ = true;
}

bool DiffRobotHW::waitForState(const ros::WallDuration& timeout)
{
  fresh_ = false;
  queue_.callAvailable(timeout);  // one lockstep period: the simulator waits for our answer
  if (!fresh_)
    return false;
  state_time_ = state_->header.stamp;
  return true;
}

void DiffRobotHW::read(const ros::Time& /*time*/, const ros::Duration& /*period*/)
{
  if (!state_)
    return;
  const sensor_msgs::JointState& s = *state_;
  for (std::size_t i = 0; i < joint_names_.size(); ++i)
  {
    for (std::size_t k = 0; k < s.name.size(); ++k)
    {
      if (s.name[k] != joint_names_[i])
        continue;
      pos_[i] = k < s.position.size() ? s.position[k] : pos_[i];
      vel_[i] = k < s.velocity.size() ? s.velocity[k] : vel_[i];
      eff_[i] = k < s.effort.size() ? s.effort[k] : eff_[i];
    }
  }
}

void DiffRobotHW::write(const ros::Time& time, const ros::Duration& /*period*/)
{
  sensor_msgs::JointState cmd;
  cmd.header.stamp = time;  // answers the state of this time
  cmd.name = joint_names_;
  cmd.effort = cmd_;
  command_pub_.publish(cmd);
}

}  // namespace my_robot_simulation_control
