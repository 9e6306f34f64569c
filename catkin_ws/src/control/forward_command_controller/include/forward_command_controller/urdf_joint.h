// The URDF joint of the position PID controllers (forward_command_controller's
// JointPositionPidController, effort_controllers' JointGroupPositionController): looked up and
// checked in init(), its limits and the position error in update(), written once. Its users
// find_package(angles) and urdf (as for joint_position_pid_controller.h).
#pragma once

#include <string>

#include <angles/angles.h>
#include <ros/console.h>
#include <urdf/model.h>

namespace forward_command_controller
{
namespace internal
{

/// Joint `joint_name` of the URDF, which must have a <limit> when revolute or prismatic; null with
/// an ERROR otherwise. `where` is appended to the messages (e.g. " (namespace: /arm)" or "").
inline urdf::JointConstSharedPtr getUrdfJoint(const urdf::Model& urdf, const std::string& joint_name,
                                              const std::string& where)
{
  urdf::JointConstSharedPtr joint_urdf = urdf.getJoint(joint_name);
  if (!joint_urdf)
  {
    ROS_ERROR("Could not find joint '%s' in urdf", joint_name.c_str());
    return nullptr;
  }
  if ((joint_urdf->type == urdf::Joint::REVOLUTE || joint_urdf->type == urdf::Joint::PRISMATIC) && !joint_urdf->limits)
  {
    ROS_ERROR("Joint '%s' has no <limit> in the urdf%s", joint_name.c_str(), where.c_str());
    return nullptr;
  }
  return joint_urdf;
}

/// A position command [rad or m] clamped to the URDF limits of a revolute or prismatic joint
/// (unchanged for other joints, or without a URDF joint).
inline void enforceJointLimits(const urdf::JointConstSharedPtr& joint_urdf, double& command)
{
  if (joint_urdf && joint_urdf->limits &&
      (joint_urdf->type == urdf::Joint::REVOLUTE || joint_urdf->type == urdf::Joint::PRISMATIC))
  {
    if (command > joint_urdf->limits->upper)
      command = joint_urdf->limits->upper;
    else if (command < joint_urdf->limits->lower)
      command = joint_urdf->limits->lower;
  }
}

/// Position error command - current: the shortest angle within the limits for a revolute joint,
/// the shortest angle for a continuous joint, the difference otherwise (or without a URDF joint).
inline double positionError(const urdf::JointConstSharedPtr& joint_urdf, double current, double command)
{
  double error = command - current;
  if (joint_urdf && joint_urdf->type == urdf::Joint::REVOLUTE)
    angles::shortest_angular_distance_with_large_limits(current, command, joint_urdf->limits->lower,
                                                        joint_urdf->limits->upper, error);
  else if (joint_urdf && joint_urdf->type == urdf::Joint::CONTINUOUS)
    error = angles::shortest_angular_distance(current, command);
  return error;
}

}  // namespace internal
}  // namespace forward_command_controller
