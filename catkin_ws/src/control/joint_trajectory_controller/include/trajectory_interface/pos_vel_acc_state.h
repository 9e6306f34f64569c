// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <vector>

namespace trajectory_interface
{
/**
 * \brief Position, velocity and acceleration of a set of joints at one instant.
 *
 * An empty \c velocity or \c acceleration means "not given": a segment built from such states uses
 * a lower-order spline (see QuinticSplineSegment).
 */
template <class ScalarType>
struct PosVelAccState
{
  typedef ScalarType Scalar;

  PosVelAccState() = default;

  /// All three vectors of size \p size, zero-filled.
  explicit PosVelAccState(typename std::vector<Scalar>::size_type size)
    : position(size, Scalar(0)), velocity(size, Scalar(0)), acceleration(size, Scalar(0))
  {
  }

  std::vector<Scalar> position;
  std::vector<Scalar> velocity;
  std::vector<Scalar> acceleration;
};

}  // namespace trajectory_interface
