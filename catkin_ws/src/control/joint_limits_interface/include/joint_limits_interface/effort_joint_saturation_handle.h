// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/limits_handle.h>
#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>

namespace joint_limits_interface
{
/**
 * \brief Saturates the command of an effort-controlled joint without soft limits.
 *
 * The command is clamped to ±max_effort; beyond a position limit, or beyond ±max_velocity, the
 * effort that would push further out is cut to 0 (e.g. position above max_position ⇒ effort ≤ 0).
 * Requires velocity and effort limits (throws JointLimitsInterfaceException otherwise).
 */
class EffortJointSaturationHandle
{
public:
  EffortJointSaturationHandle() = default;

  EffortJointSaturationHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits)
    : jh_(jh), limits_(limits)
  {
    internal::requireLimits(limits.has_velocity_limits, getName(), "velocity");
    internal::requireLimits(limits.has_effort_limits, getName(), "efforts");  // the original's wording
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& /*period*/)
  {
    double min_eff = -limits_.max_effort;
    double max_eff = limits_.max_effort;

    if (limits_.has_position_limits)
    {
      const double pos = jh_.getPosition();
      if (pos < limits_.min_position)
        min_eff = 0.0;
      else if (pos > limits_.max_position)
        max_eff = 0.0;
    }

    const double vel = jh_.getVelocity();
    if (vel < -limits_.max_velocity)
      min_eff = 0.0;
    else if (vel > limits_.max_velocity)
      max_eff = 0.0;

    jh_.setCommand(internal::saturate(jh_.getCommand(), min_eff, max_eff));
  }

  /// Stateless: nothing to reset.
  void reset() {}

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
};

}  // namespace joint_limits_interface
