// The diffbot of diff_drive_controller's tests: a fake RobotHW whose wheel joints
// `wheel_<i>_joint` follow their velocity commands exactly (VelocityJointInterface +
// JointStateInterface). Services `start` / `stop`: while stopped, positions and velocities read
// NaN (a disconnected robot); after `start` the wheels continue from where they were.
#pragma once

#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

class Diffbot : public hardware_interface::RobotHW
{
public:
  explicit Diffbot(unsigned int num_joints = 2)
    : running_(true)
    , cmd_(num_joints, 0.0)
    , pos_(num_joints, 0.0)
    , vel_(num_joints, 0.0)
    , eff_(num_joints, 0.0)
    , last_valid_pos_(num_joints, 0.0)
    , start_srv_(nh_.advertiseService("start", &Diffbot::startCallback, this))
    , stop_srv_(nh_.advertiseService("stop", &Diffbot::stopCallback, this))
  {
    for (unsigned int i = 0; i < num_joints; ++i)
    {
      std::ostringstream os;
      os << "wheel_" << i << "_joint";
      hardware_interface::JointStateHandle state_handle(os.str(), &pos_[i], &vel_[i], &eff_[i]);
      jnt_state_interface_.registerHandle(state_handle);
      jnt_vel_interface_.registerHandle(hardware_interface::JointHandle(state_handle, &cmd_[i]));
    }
    registerInterface(&jnt_state_interface_);
    registerInterface(&jnt_vel_interface_);
  }

  /// Control period [s].
  ros::Duration getPeriod() const { return ros::Duration(0.01); }

  void read(const ros::Time& /*time*/, const ros::Duration& period) override
  {
    if (running_)
    {
      for (std::size_t i = 0; i < pos_.size(); ++i)
      {
        if (std::isnan(pos_[i]))  // first cycle after start(): the wheels did not move meanwhile
        {
          pos_[i] = last_valid_pos_[i];
          vel_[i] = 0.0;
        }
        pos_[i] += vel_[i] * period.toSec();
        vel_[i] = cmd_[i];
      }
    }
    else
    {
      for (std::size_t i = 0; i < pos_.size(); ++i)
        if (!std::isnan(pos_[i]))
          last_valid_pos_[i] = pos_[i];
      std::fill(pos_.begin(), pos_.end(), std::numeric_limits<double>::quiet_NaN());
      std::fill(vel_.begin(), vel_.end(), std::numeric_limits<double>::quiet_NaN());
    }
  }

  void write(const ros::Time& /*time*/, const ros::Duration& /*period*/) override {}

private:
  bool startCallback(std_srvs::Empty::Request&, std_srvs::Empty::Response&)
  {
    running_ = true;
    return true;
  }

  bool stopCallback(std_srvs::Empty::Request&, std_srvs::Empty::Response&)
  {
    running_ = false;
    return true;
  }

  std::atomic<bool> running_;
  hardware_interface::JointStateInterface jnt_state_interface_;
  hardware_interface::VelocityJointInterface jnt_vel_interface_;
  std::vector<double> cmd_, pos_, vel_, eff_;
  std::vector<double> last_valid_pos_;  ///< positions when the robot was stopped
  ros::NodeHandle nh_;
  ros::ServiceServer start_srv_;
  ros::ServiceServer stop_srv_;
};
