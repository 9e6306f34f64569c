// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <algorithm>

namespace joint_limits_interface
{
namespace internal
{
/// \p val clamped to [\p min_val, \p max_val] (\p max_val wins if the bounds cross).
inline double saturate(const double val, const double min_val, const double max_val)
{
  return std::min(std::max(val, min_val), max_val);
}
}  // namespace internal
}  // namespace joint_limits_interface
