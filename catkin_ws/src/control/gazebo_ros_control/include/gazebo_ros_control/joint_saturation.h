// URDF limit enforcement on one joint command, with joint_limits_interface's saturation
// semantics (as DefaultRobotHWSim registers them). No ROS: the period is in seconds.
#ifndef GAZEBO_ROS_CONTROL_JOINT_SATURATION_H
#define GAZEBO_ROS_CONTROL_JOINT_SATURATION_H

#include <gazebo_ros_control/bridge_joint.h>

namespace gazebo_ros_control
{

class JointSaturation
{
public:
  explicit JointSaturation(const BridgeJoint& joint);

  /// The command after limit enforcement. NaN (no command yet) stays NaN.
  /// - effort: clamped to ±effort; no push further out past a position limit or beyond
  ///   the velocity limit (EffortJointSaturationHandle);
  /// - velocity: clamped to ±velocity (VelocityJointSaturationHandle);
  /// - position: clamped to [lower, upper] and to the previous command ± velocity·period
  ///   (PositionJointSaturationHandle; the first previous command is the joint position).
  /// @param position [rad|m], velocity [rad/s|m/s]: the joint's current state
  /// @param period [s]: the control period
  double enforce(double command, double position, double velocity, double period);

  /// Forgets the previous position command (after an e-stop or a reset).
  void reset();

private:
  BridgeJoint joint_;
  double prev_cmd_;
};

}  // namespace gazebo_ros_control

#endif  // GAZEBO_ROS_CONTROL_JOINT_SATURATION_H
