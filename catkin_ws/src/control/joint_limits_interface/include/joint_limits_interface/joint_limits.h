// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

namespace joint_limits_interface
{
/**
 * \brief Hard limits of one joint (positions [rad or m], velocities [rad/s or m/s],
 * accelerations [rad/s² or m/s²], jerks [rad/s³ or m/s³], efforts [N·m or N]).
 *
 * A limit is only meaningful when its \c has_*_limits flag is set; everything is off by default.
 * \c angle_wraparound marks a joint without position limits whose angle wraps (continuous joint).
 */
struct JointLimits
{
  double min_position = 0.0;
  double max_position = 0.0;
  double max_velocity = 0.0;
  double max_acceleration = 0.0;
  double max_jerk = 0.0;
  double max_effort = 0.0;

  bool has_position_limits = false;
  bool has_velocity_limits = false;
  bool has_acceleration_limits = false;
  bool has_jerk_limits = false;
  bool has_effort_limits = false;
  bool angle_wraparound = false;
};

/**
 * \brief Soft limits of one joint, as in the URDF's \c <safety_controller> element.
 *
 * Near \c min_position / \c max_position the allowed velocity shrinks with gain \c k_position [1/s];
 * \c k_velocity [effort·s/position] does the same for the effort as a function of the velocity error.
 */
struct SoftJointLimits
{
  double min_position = 0.0;
  double max_position = 0.0;
  double k_position = 0.0;
  double k_velocity = 0.0;
};

}  // namespace joint_limits_interface
