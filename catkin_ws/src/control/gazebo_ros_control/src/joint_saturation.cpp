#include <gazebo_ros_control/joint_saturation.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace gazebo_ros_control
{

namespace
{
double saturate(double v, double lo, double hi) { return std::min(std::max(v, lo), hi); }
}  // namespace

JointSaturation::JointSaturation(const BridgeJoint& joint)
  : joint_(joint), prev_cmd_(std::numeric_limits<double>::quiet_NaN())
{
}

void JointSaturation::reset() { prev_cmd_ = std::numeric_limits<double>::quiet_NaN(); }

double JointSaturation::enforce(double command, double position, double velocity, double period)
{
  if (std::isnan(command))
    return command;
  switch (joint_.interface)
  {
    case JointInterface::EFFORT:
    {
      if (!joint_.has_effort_limit)
        return command;
      double lo = -joint_.effort;
      double hi = joint_.effort;
      if (joint_.has_position_limits)
      {
        if (position < joint_.lower)
          lo = 0.0;
        else if (position > joint_.upper)
          hi = 0.0;
      }
      if (joint_.has_velocity_limit)
      {
        if (velocity < -joint_.velocity)
          lo = 0.0;
        else if (velocity > joint_.velocity)
          hi = 0.0;
      }
      return saturate(command, lo, hi);
    }
    case JointInterface::VELOCITY:
      if (!joint_.has_velocity_limit)
        return command;
      return saturate(command, -joint_.velocity, joint_.velocity);
    case JointInterface::POSITION:
    {
      if (!joint_.has_position_limits && !joint_.has_velocity_limit)
        return command;
      double lo = -std::numeric_limits<double>::infinity();
      double hi = std::numeric_limits<double>::infinity();
      if (joint_.has_position_limits)
      {
        lo = joint_.lower;
        hi = joint_.upper;
      }
      if (joint_.has_velocity_limit && period > 0.0)
      {
        if (std::isnan(prev_cmd_))
          prev_cmd_ = position;
        const double step = joint_.velocity * period;
        lo = std::max(prev_cmd_ - step, lo);
        hi = std::min(prev_cmd_ + step, hi);
      }
      const double out = saturate(command, lo, hi);
      prev_cmd_ = out;
      return out;
    }
    case JointInterface::STATE:
      break;
  }
  return command;
}

}  // namespace gazebo_ros_control
