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
    const double pos = limits_.has_position_limits ? jh_.getPosition() : 0.0;
    auto range = internal::softVelocityRange(limits_, soft_limits_, pos, max_vel_limit_);
    if (limits_.has_acceleration_limits)
      internal::limitAcceleration(limits_, jh_.getVelocity(), period.toSec(), range.first, range.second);
    jh_.setCommand(internal::saturate(jh_.getCommand(), range.first, range.second));
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
