// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/saturate.h>
#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>

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
    if (!limits.has_velocity_limits)
      throw JointLimitsInterfaceException("Cannot enforce limits for joint '" + getName() +
                                          "'. It has no velocity limits specification.");
  }

  std::string getName() const { return jh_.getName(); }

  /// \param period control period, > 0
  void enforceLimits(const ros::Duration& period)
  {
    using internal::saturate;
    if (std::isnan(prev_cmd_))
      prev_cmd_ = jh_.getPosition();
    const double pos = prev_cmd_;

    double soft_min_vel = -limits_.max_velocity;
    double soft_max_vel = limits_.max_velocity;
    if (limits_.has_position_limits)
    {
      soft_min_vel = saturate(-soft_limits_.k_position * (pos - soft_limits_.min_position), -limits_.max_velocity,
                              limits_.max_velocity);
      soft_max_vel = saturate(-soft_limits_.k_position * (pos - soft_limits_.max_position), -limits_.max_velocity,
                              limits_.max_velocity);
    }

    const double dt = period.toSec();
    double pos_low = pos + soft_min_vel * dt;
    double pos_high = pos + soft_max_vel * dt;
    if (limits_.has_position_limits)
    {
      // guards against soft limits configured beyond the hard ones
      pos_low = std::max(pos_low, limits_.min_position);
      pos_high = std::min(pos_high, limits_.max_position);
    }

    const double cmd = saturate(jh_.getCommand(), pos_low, pos_high);
    jh_.setCommand(cmd);
    prev_cmd_ = cmd;
  }

  /// Forget the previous command (after a mode switch or an e-stop).
  void reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
  double prev_cmd_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace joint_limits_interface
