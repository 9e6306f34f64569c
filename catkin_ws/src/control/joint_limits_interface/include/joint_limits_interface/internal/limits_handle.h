// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
// What the saturation and soft-limits handles share, written once (not part of the original's API).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <hardware_interface/joint_command_interface.h>

#include <joint_limits_interface/internal/saturate.h>
#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>

namespace joint_limits_interface
{
namespace internal
{
/// Throws "Cannot enforce limits for joint 'NAME'. It has no WHAT limits specification." unless \p has_limits.
inline void requireLimits(bool has_limits, const std::string& joint_name, const std::string& what)
{
  if (!has_limits)
    throw JointLimitsInterfaceException("Cannot enforce limits for joint '" + joint_name + "'. It has no " + what +
                                        " limits specification.");
}

/// The velocity range [min, max] the soft limits allow at position \p pos:
/// [sat(-k_position·(pos - soft_min)), sat(-k_position·(pos - soft_max))], sat() clamping to
/// ±\p max_vel; ±\p max_vel when the joint has no position limits.
inline std::pair<double, double> softVelocityRange(const JointLimits& limits, const SoftJointLimits& soft_limits,
                                                   double pos, double max_vel)
{
  if (!limits.has_position_limits)
    return { -max_vel, max_vel };
  return { saturate(-soft_limits.k_position * (pos - soft_limits.min_position), -max_vel, max_vel),
           saturate(-soft_limits.k_position * (pos - soft_limits.max_position), -max_vel, max_vel) };
}

/// Narrows the velocity range [\p low, \p high] to within max_acceleration·period of the measured
/// velocity \p vel when the joint has acceleration limits.
inline void limitAcceleration(const JointLimits& limits, double vel, double period, double& low, double& high)
{
  if (!limits.has_acceleration_limits)
    return;
  const double dv = limits.max_acceleration * period;
  low = std::max(vel - dv, low);
  high = std::min(vel + dv, high);
}

/// The previous (limited) command of the position handles: the joint's measured position before
/// the first command and after reset().
class PreviousPositionCommand
{
public:
  double get(const hardware_interface::JointHandle& jh)
  {
    if (std::isnan(prev_cmd_))
      prev_cmd_ = jh.getPosition();
    return prev_cmd_;
  }

  /// Clamps the joint's command to [\p low, \p high], sets and remembers it.
  void apply(hardware_interface::JointHandle& jh, double low, double high)
  {
    prev_cmd_ = saturate(jh.getCommand(), low, high);
    jh.setCommand(prev_cmd_);
  }

  void reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

private:
  double prev_cmd_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace internal
}  // namespace joint_limits_interface
