// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <stdexcept>
#include <string>

#include <hardware_interface/internal/resource_manager.h>
#include <ros/duration.h>

#include <joint_limits_interface/effort_joint_saturation_handle.h>
#include <joint_limits_interface/effort_joint_soft_limits_handle.h>
#include <joint_limits_interface/joint_limits.h>
#include <joint_limits_interface/joint_limits_interface_exception.h>
#include <joint_limits_interface/position_joint_saturation_handle.h>
#include <joint_limits_interface/position_joint_soft_limits_handle.h>
#include <joint_limits_interface/velocity_joint_saturation_handle.h>
#include <joint_limits_interface/velocity_joint_soft_limits_handle.h>

namespace joint_limits_interface
{
/**
 * \brief A set of limits handles (one per joint) enforced together.
 *
 * Typical use in a RobotHW: register one handle per joint in init(), then call enforceLimits(period)
 * in write() before sending the commands, and reset() after a mode switch or an e-stop.
 * \tparam HandleType provides getName(), enforceLimits(const ros::Duration&) and reset().
 */
template <class HandleType>
class JointLimitsInterface : public hardware_interface::ResourceManager<HandleType>
{
public:
  /// Throws JointLimitsInterfaceException if \p name is not registered.
  HandleType getHandle(const std::string& name)
  {
    try
    {
      return hardware_interface::ResourceManager<HandleType>::getHandle(name);
    }
    catch (const std::logic_error& e)
    {
      throw JointLimitsInterfaceException(e.what());
    }
  }

  /// Enforce the limits of every registered handle (real-time safe).
  void enforceLimits(const ros::Duration& period)
  {
    for (auto& name_and_handle : this->resource_map_)
      name_and_handle.second.enforceLimits(period);
  }

  /// Reset every registered handle (real-time safe).
  void reset()
  {
    for (auto& name_and_handle : this->resource_map_)
      name_and_handle.second.reset();
  }
};

/// Position-controlled joints, saturation (no soft limits).
class PositionJointSaturationInterface : public JointLimitsInterface<PositionJointSaturationHandle>
{
};

/// Position-controlled joints with soft limits.
class PositionJointSoftLimitsInterface : public JointLimitsInterface<PositionJointSoftLimitsHandle>
{
};

/// Effort-controlled joints, saturation (no soft limits).
class EffortJointSaturationInterface : public JointLimitsInterface<EffortJointSaturationHandle>
{
};

/// Effort-controlled joints with soft limits.
class EffortJointSoftLimitsInterface : public JointLimitsInterface<EffortJointSoftLimitsHandle>
{
};

/// Velocity-controlled joints, saturation (no soft limits).
class VelocityJointSaturationInterface : public JointLimitsInterface<VelocityJointSaturationHandle>
{
};

/// Velocity-controlled joints with soft limits.
class VelocityJointSoftLimitsInterface : public JointLimitsInterface<VelocityJointSoftLimitsHandle>
{
};

}  // namespace joint_limits_interface
