// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <algorithm>
#include <limits>
#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/saturate.h>
#include <joint_limits_interface/joint_limits.h>

namespace joint_limits_interface
{
/**
 * \brief Limits the command of a velocity-controlled joint with soft limits.
 *
 * With position limits, the measured position p gives the range
 * [sat(-k_position·(p - soft_min)), sat(-k_position·(p - soft_max))], sat() clamping to
 * ±max_velocity (unbounded if the joint has no velocity limits); with acceleration limits the
 * range is further restricted to within max_acceleration·period of the measured velocity.
 */
class VelocityJointSoftLimitsHandle
{
public:
  VelocityJointSoftLimitsHandle() = default;

  VelocityJointSoftLimitsHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits,
                                const SoftJointLimits& soft_limits)
    : jh_(jh), limits_(limits), soft_limits_(soft_limits)
  {
    if (limits.has_velocity_limits)
      max_vel_limit_ = limits.max_velocity;
  }

  std::string getName() const { return jh_.getName(); }

  /// \param period control period (used with acceleration limits)
  void enforceLimits(const ros::Duration& period)
  {
    using internal::saturate;
    double min_vel = -max_vel_limit_;
    double max_vel = max_vel_limit_;
    if (limits_.has_position_limits)
    {
      const double pos = jh_.getPosition();
      min_vel = saturate(-soft_limits_.k_position * (pos - soft_limits_.min_position), -max_vel_limit_,
                         max_vel_limit_);
      max_vel = saturate(-soft_limits_.k_position * (pos - soft_limits_.max_position), -max_vel_limit_,
                         max_vel_limit_);
    }
    if (limits_.has_acceleration_limits)
    {
      const double vel = jh_.getVelocity();
      const double dv = limits_.max_acceleration * period.toSec();
      min_vel = std::max(vel - dv, min_vel);
      max_vel = std::min(vel + dv, max_vel);
    }
    jh_.setCommand(saturate(jh_.getCommand(), min_vel, max_vel));
  }

  /// Stateless: nothing to reset.
  void reset() {}

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
  double max_vel_limit_ = std::numeric_limits<double>::max();
};

}  // namespace joint_limits_interface
