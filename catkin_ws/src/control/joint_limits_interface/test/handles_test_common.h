// What the limits handles' tests share: a joint's raw data, the exception text of a call, the
// usual limits and control period.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <joint_limits_interface/joint_limits_interface.h>

using namespace joint_limits_interface;

namespace
{
const double EPS = 1e-12;

/// One joint's raw data, as a RobotHW would hold it.
struct JointData
{
  double pos = 0.0;
  double vel = 0.0;
  double eff = 0.0;
  double cmd = 0.0;

  hardware_interface::JointHandle handle(const std::string& name = "joint")
  {
    return hardware_interface::JointHandle(hardware_interface::JointStateHandle(name, &pos, &vel, &eff), &cmd);
  }
};

inline std::string errorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const JointLimitsInterfaceException& e)
  {
    return e.what();
  }
  return "";
}

/// pos [-1, 1], vel 2, no other limits.
inline JointLimits positionVelocityLimits()
{
  JointLimits l;
  l.has_position_limits = true;
  l.min_position = -1.0;
  l.max_position = 1.0;
  l.has_velocity_limits = true;
  l.max_velocity = 2.0;
  return l;
}

/// pos [-1, 1], vel 2, effort 10.
inline JointLimits effortLimits()
{
  JointLimits l = positionVelocityLimits();
  l.has_effort_limits = true;
  l.max_effort = 10.0;
  return l;
}

/// effortLimits(); soft [-0.5, 0.5], k_position 10, k_velocity 5.
inline SoftJointLimits effortSoftLimits()
{
  SoftJointLimits s;
  s.min_position = -0.5;
  s.max_position = 0.5;
  s.k_position = 10.0;
  s.k_velocity = 5.0;
  return s;
}

const ros::Duration PERIOD(0.1);
}  // namespace
