// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/saturate.h>
#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>

namespace joint_limits_interface
{
/**
 * \brief Limits the command of an effort-controlled joint with soft limits.
 *
 * From the measured position p the velocity range [v_min, v_max] is
 * [sat_v(-k_position·(p - soft_min)), sat_v(-k_position·(p - soft_max))] (±max_velocity without
 * position limits); from the measured velocity v the effort range is
 * [sat_e(-k_velocity·(v - v_min)), sat_e(-k_velocity·(v - v_max))], sat_v/sat_e clamping to
 * ±max_velocity/±max_effort. Requires velocity and effort limits.
 */
class EffortJointSoftLimitsHandle
{
public:
  EffortJointSoftLimitsHandle() = default;

  EffortJointSoftLimitsHandle(const hardware_interface::JointHandle& jh, const JointLimits& limits,
                              const SoftJointLimits& soft_limits)
    : jh_(jh), limits_(limits), soft_limits_(soft_limits)
  {
    if (!limits.has_velocity_limits)
      throw JointLimitsInterfaceException("Cannot enforce limits for joint '" + getName() +
                                          "'. It has no velocity limits specification.");
    if (!limits.has_effort_limits)
      throw JointLimitsInterfaceException("Cannot enforce limits for joint '" + getName() +
                                          "'. It has no effort limits specification.");
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& /*period*/)
  {
    using internal::saturate;
    const double pos = jh_.getPosition();
    const double vel = jh_.getVelocity();

    double soft_min_vel = -limits_.max_velocity;
    double soft_max_vel = limits_.max_velocity;
    if (limits_.has_position_limits)
    {
      soft_min_vel = saturate(-soft_limits_.k_position * (pos - soft_limits_.min_position), -limits_.max_velocity,
                              limits_.max_velocity);
      soft_max_vel = saturate(-soft_limits_.k_position * (pos - soft_limits_.max_position), -limits_.max_velocity,
                              limits_.max_velocity);
    }

    const double soft_min_eff =
        saturate(-soft_limits_.k_velocity * (vel - soft_min_vel), -limits_.max_effort, limits_.max_effort);
    const double soft_max_eff =
        saturate(-soft_limits_.k_velocity * (vel - soft_max_vel), -limits_.max_effort, limits_.max_effort);

    jh_.setCommand(saturate(jh_.getCommand(), soft_min_eff, soft_max_eff));
  }

  /// Stateless: nothing to reset.
  void reset() {}

private:
  hardware_interface::JointHandle jh_;
  JointLimits limits_;
  SoftJointLimits soft_limits_;
};

}  // namespace joint_limits_interface
