// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <algorithm>
#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/limits_handle.h>
#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>

namespace joint_limits_interface
{
/**
 * \brief Saturates the command of a velocity-controlled joint.
 *
 * The command is clamped to ±max_velocity and, with acceleration limits, to within
 * max_acceleration·period of the measured velocity. Requires velocity limits.
 */
class VelocityJointSaturationHandle
{
public:
  VelocityJointSaturationHandle() = default;

  VelocityJointSaturationHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits)
    : jh_(jh), limits_(limits)
  {
    internal::requireLimits(limits.has_velocity_limits, getName(), "velocity");
  }

  std::string getName() const { return jh_.getName(); }

  /// \param period control period (used with acceleration limits)
  void enforceLimits(const ros::Duration& period)
  {
    double vel_low = -limits_.max_velocity;
    double vel_high = limits_.max_velocity;
    if (limits_.has_acceleration_limits)
      internal::limitAcceleration(limits_, jh_.getVelocity(), period.toSec(), vel_low, vel_high);
    jh_.setCommand(internal::saturate(jh_.getCommand(), vel_low, vel_high));
  }

  /// Stateless: nothing to reset.
  void reset() {}

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
};

}  // namespace joint_limits_interface
