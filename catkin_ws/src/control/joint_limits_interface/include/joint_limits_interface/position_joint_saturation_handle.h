// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/saturate.h>
#include <joint_limits_interface/joint_limits.h>

namespace joint_limits_interface
{
/**
 * \brief Saturates the command of a position-controlled joint without soft limits.
 *
 * The command is clamped to [min_position, max_position] (if the joint has position limits) and,
 * if it has velocity limits, to within max_velocity·period of the previous (limited) command.
 * The first call after construction or reset() starts from the joint's measured position.
 */
class PositionJointSaturationHandle
{
public:
  PositionJointSaturationHandle() = default;

  PositionJointSaturationHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits)
    : jh_(jh), limits_(limits)
  {
    if (limits_.has_position_limits)
    {
      min_pos_limit_ = limits_.min_position;
      max_pos_limit_ = limits_.max_position;
    }
  }

  std::string getName() const { return jh_.getName(); }

  /// \param period control period (used with velocity limits)
  void enforceLimits(const ros::Duration& period)
  {
    if (std::isnan(prev_cmd_))
      prev_cmd_ = jh_.getPosition();

    double min_pos = min_pos_limit_;
    double max_pos = max_pos_limit_;
    if (limits_.has_velocity_limits)
    {
      const double delta_pos = limits_.max_velocity * period.toSec();
      min_pos = std::max(prev_cmd_ - delta_pos, min_pos_limit_);
      max_pos = std::min(prev_cmd_ + delta_pos, max_pos_limit_);
    }

    const double cmd = internal::saturate(jh_.getCommand(), min_pos, max_pos);
    jh_.setCommand(cmd);
    prev_cmd_ = cmd;
  }

  /// Forget the previous command (after a mode switch or an e-stop).
  void reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  double min_pos_limit_ = -std::numeric_limits<double>::max();
  double max_pos_limit_ = std::numeric_limits<double>::max();
  double prev_cmd_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace joint_limits_interface
