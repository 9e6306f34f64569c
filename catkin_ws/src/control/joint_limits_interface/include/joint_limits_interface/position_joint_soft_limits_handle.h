// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <algorithm>
#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/limits_handle.h>
#include <joint_limits_interface/joint_limits.h>

namespace joint_limits_interface
{
/**
 * \brief Limits the command of a position-controlled joint with soft limits (open loop).
 *
 * From the previous command p, the allowed velocity range is
 * [sat(-k_position·(p - soft_min)), sat(-k_position·(p - soft_max))] with sat() clamping to
 * ±max_velocity (only ±max_velocity without position limits); the command is clamped to
 * p + range·period and then to the hard position limits. k_velocity is not used.
 * Requires velocity limits (throws JointLimitsInterfaceException otherwise).
 */
class PositionJointSoftLimitsHandle
{
public:
  PositionJointSoftLimitsHandle() = default;

  PositionJointSoftLimitsHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits,
                                const SoftJointLimits& soft_limits)
    : jh_(jh), limits_(limits), soft_limits_(soft_limits)
  {
    internal::requireLimits(limits.has_velocity_limits, getName(), "velocity");
  }

  std::string getName() const { return jh_.getName(); }

  /// \param period control period, > 0
  void enforceLimits(const ros::Duration& period)
  {
    const double pos = prev_cmd_.get(jh_);
    const auto vel_range = internal::softVelocityRange(limits_, soft_limits_, pos, limits_.max_velocity);

    const double dt = period.toSec();
    double pos_low = pos + vel_range.first * dt;
    double pos_high = pos + vel_range.second * dt;
    if (limits_.has_position_limits)
    {
      // guards against soft limits configured beyond the hard ones
      pos_low = std::max(pos_low, limits_.min_position);
      pos_high = std::min(pos_high, limits_.max_position);
    }

    prev_cmd_.apply(jh_, pos_low, pos_high);
  }

  /// Forget the previous command (after a mode switch or an e-stop).
  void reset() { prev_cmd_.reset(); }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
  internal::PreviousPositionCommand prev_cmd_;
};

}  // namespace joint_limits_interface
