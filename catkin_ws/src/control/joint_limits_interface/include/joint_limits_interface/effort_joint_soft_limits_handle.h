// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>

#include <hardware_interface/joint_command_interface.h>
#include <ros/duration.h>

#include <joint_limits_interface/internal/limits_handle.h>
#include <joint_limits_interface/joint_limits.h>

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
    internal::requireLimits(limits.has_velocity_limits, getName(), "velocity");
    internal::requireLimits(limits.has_effort_limits, getName(), "effort");
  }

  std::string getName() const { return jh_.getName(); }

  void enforceLimits(const ros::Duration& /*period*/)
  {
    using internal::saturate;
    const double pos = jh_.getPosition();
    const double vel = jh_.getVelocity();

    const auto vel_range = internal::softVelocityRange(limits_, soft_limits_, pos, limits_.max_velocity);

    const double soft_min_eff =
        saturate(-soft_limits_.k_velocity * (vel - vel_range.first), -limits_.max_effort, limits_.max_effort);
    const double soft_max_eff =
        saturate(-soft_limits_.k_velocity * (vel - vel_range.second), -limits_.max_effort, limits_.max_effort);

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
