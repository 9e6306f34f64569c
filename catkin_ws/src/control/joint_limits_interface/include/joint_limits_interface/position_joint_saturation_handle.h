// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <algorithm>
#include <limits>
#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/limits_handle.h>
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
    const double prev_cmd = prev_cmd_.get(jh_);
    double min_pos = min_pos_limit_;
    double max_pos = max_pos_limit_;
    if (limits_.has_velocity_limits)
    {
      const double delta_pos = limits_.max_velocity * period.toSec();
      min_pos = std::max(prev_cmd - delta_pos, min_pos_limit_);
      max_pos = std::min(prev_cmd + delta_pos, max_pos_limit_);
    }
    prev_cmd_.apply(jh_, min_pos, max_pos);
  }

  /// Forget the previous command (after a mode switch or an e-stop).
  void reset() { prev_cmd_.reset(); }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  double min_pos_limit_ = -std::numeric_limits<double>::max();
  double max_pos_limit_ = std::numeric_limits<double>::max();
  internal::PreviousPositionCommand prev_cmd_;
};

}  // namespace joint_limits_interface
