// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <vector>

namespace trajectory_interface
{
/// Position, velocity, acceleration and effort of a set of joints (empty vector: not given).
template <class ScalarType>
struct PosVelAccEffState
{
  typedef ScalarType Scalar;

  PosVelAccEffState() = default;

  /// All four vectors of size \p size, zero-filled.
  explicit PosVelAccEffState(typename std::vector<Scalar>::size_type size)
    : position(size, Scalar(0)), velocity(size, Scalar(0)), acceleration(size, Scalar(0)), effort(size, Scalar(0))
  {
  }

  std::vector<Scalar> position;
  std::vector<Scalar> velocity;
  std::vector<Scalar> acceleration;
  std::vector<Scalar> effort;
};

}  // namespace trajectory_interface
