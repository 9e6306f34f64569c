// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <urdf/urdfdom_compatibility.h>
#include <urdf_model/joint.h>

#include <joint_limits_interface/joint_limits.h>

namespace joint_limits_interface
{
/**
 * \brief Fill \p limits from a URDF joint's \c <limit> element.
 *
 * Revolute and prismatic joints get position limits (lower, upper); a continuous joint gets
 * \c angle_wraparound instead. Velocity and effort limits are always set from the element;
 * acceleration and jerk limits are left untouched (URDF has none).
 * \return false (and \p limits unchanged) if the joint is null or has no \c <limit> element.
 */
inline bool getJointLimits(urdf::JointConstSharedPtr urdf_joint, JointLimits& limits)
{
  if (!urdf_joint || !urdf_joint->limits)
    return false;

  limits.has_position_limits = urdf_joint->type == urdf::Joint::REVOLUTE || urdf_joint->type == urdf::Joint::PRISMATIC;
  if (limits.has_position_limits)
  {
    limits.min_position = urdf_joint->limits->lower;
    limits.max_position = urdf_joint->limits->upper;
  }
  else if (urdf_joint->type == urdf::Joint::CONTINUOUS)
  {
    limits.angle_wraparound = true;
  }

  limits.has_velocity_limits = true;
  limits.max_velocity = urdf_joint->limits->velocity;

  limits.has_acceleration_limits = false;

  limits.has_effort_limits = true;
  limits.max_effort = urdf_joint->limits->effort;

  return true;
}

/**
 * \brief Fill \p soft_limits from a URDF joint's \c <safety_controller> element
 * (soft_lower_limit, soft_upper_limit, k_position, k_velocity).
 * \return false (and \p soft_limits unchanged) if the joint is null or has no such element.
 */
inline bool getSoftJointLimits(urdf::JointConstSharedPtr urdf_joint, SoftJointLimits& soft_limits)
{
  if (!urdf_joint || !urdf_joint->safety)
    return false;

  soft_limits.min_position = urdf_joint->safety->soft_lower_limit;
  soft_limits.max_position = urdf_joint->safety->soft_upper_limit;
  soft_limits.k_position = urdf_joint->safety->k_position;
  soft_limits.k_velocity = urdf_joint->safety->k_velocity;
  return true;
}

}  // namespace joint_limits_interface
