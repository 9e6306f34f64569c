// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>

#include <ros/node_handle.h>

#include <joint_limits_interface/joint_limits.h>

namespace joint_limits_interface
{
namespace internal
{
/// The limits' namespace \c joint_limits/<joint_name> under \p nh; false if it is absent or invalid.
inline bool getJointLimitsNodeHandle(const std::string& joint_name, const ros::NodeHandle& nh,
                                     ros::NodeHandle& limits_nh)
{
  const std::string limits_namespace = "joint_limits/" + joint_name;
  try
  {
    if (!nh.hasParam(limits_namespace))
    {
      ROS_DEBUG_STREAM("No joint limits specification found for joint '"
                       << joint_name << "' in the parameter server (namespace "
                       << nh.getNamespace() + "/" + limits_namespace << ").");
      return false;
    }
    limits_nh = ros::NodeHandle(nh, limits_namespace);
  }
  catch (const ros::InvalidNameException& ex)
  {
    ROS_ERROR_STREAM(ex.what());
    return false;
  }
  return true;
}

/**
 * One "has_<kind>_limits" + "<max_name>" pair: has_...=false clears the flag; has_...=true sets
 * flag and value only when the value is given too. Without has_... the limit is left unchanged.
 */
inline void getOneSidedLimit(const ros::NodeHandle& limits_nh, const std::string& has_name, const std::string& max_name,
                             bool& has_limit, double& max_value)
{
  bool has = false;
  if (!limits_nh.getParam(has_name, has))
    return;
  if (!has)
  {
    has_limit = false;
    return;
  }
  double value = 0.0;
  if (limits_nh.getParam(max_name, value))
  {
    has_limit = true;
    max_value = value;
  }
}
}  // namespace internal

/**
 * \brief Overwrite the parts of \p limits given on the parameter server.
 *
 * Reads \c <nh ns>/joint_limits/<joint_name>/{has_position_limits, min_position, max_position,
 * has_velocity_limits, max_velocity, has_acceleration_limits, max_acceleration, has_jerk_limits,
 * max_jerk, has_effort_limits, max_effort, angle_wraparound}. Values that are not specified keep
 * their current value, so URDF limits can be loaded first and then refined here.
 * \return false if there is no \c joint_limits/<joint_name> namespace.
 */
inline bool getJointLimits(const std::string& joint_name, const ros::NodeHandle& nh, JointLimits& limits)
{
  ros::NodeHandle limits_nh;
  if (!internal::getJointLimitsNodeHandle(joint_name, nh, limits_nh))
    return false;

  bool has_position_limits = false;
  if (limits_nh.getParam("has_position_limits", has_position_limits))
  {
    if (!has_position_limits)
    {
      limits.has_position_limits = false;
      bool angle_wraparound = false;
      if (limits_nh.getParam("angle_wraparound", angle_wraparound))
        limits.angle_wraparound = angle_wraparound;
    }
    else
    {
      double min_pos = 0.0;
      double max_pos = 0.0;
      if (limits_nh.getParam("min_position", min_pos) && limits_nh.getParam("max_position", max_pos))
      {
        limits.has_position_limits = true;
        limits.min_position = min_pos;
        limits.max_position = max_pos;
      }
    }
  }

  internal::getOneSidedLimit(limits_nh, "has_velocity_limits", "max_velocity", limits.has_velocity_limits,
                             limits.max_velocity);
  internal::getOneSidedLimit(limits_nh, "has_acceleration_limits", "max_acceleration", limits.has_acceleration_limits,
                             limits.max_acceleration);
  internal::getOneSidedLimit(limits_nh, "has_jerk_limits", "max_jerk", limits.has_jerk_limits, limits.max_jerk);
  internal::getOneSidedLimit(limits_nh, "has_effort_limits", "max_effort", limits.has_effort_limits, limits.max_effort);
  return true;
}

/**
 * \brief Read soft limits from \c <nh ns>/joint_limits/<joint_name>/{has_soft_limits, k_position,
 * k_velocity, soft_lower_limit, soft_upper_limit}.
 * \return true only if has_soft_limits is true and all four values are given (then \p soft_limits
 * is filled); otherwise false and \p soft_limits is unchanged.
 */
inline bool getSoftJointLimits(const std::string& joint_name, const ros::NodeHandle& nh, SoftJointLimits& soft_limits)
{
  ros::NodeHandle limits_nh;
  if (!internal::getJointLimitsNodeHandle(joint_name, nh, limits_nh))
    return false;

  bool has_soft_limits = false;
  if (!limits_nh.getParam("has_soft_limits", has_soft_limits) || !has_soft_limits)
    return false;

  SoftJointLimits read;
  if (limits_nh.getParam("k_position", read.k_position) && limits_nh.getParam("k_velocity", read.k_velocity) &&
      limits_nh.getParam("soft_lower_limit", read.min_position) &&
      limits_nh.getParam("soft_upper_limit", read.max_position))
  {
    soft_limits = read;
    return true;
  }
  return false;
}

}  // namespace joint_limits_interface
