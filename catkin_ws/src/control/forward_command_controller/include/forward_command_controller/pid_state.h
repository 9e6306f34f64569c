// The control_msgs/JointControllerState a PID joint controller publishes every 10th update
// (forward_command_controller's JointPositionPidController, effort_controllers'
// JointVelocityController), filled once here. Its users find control_msgs and control_toolbox.
#pragma once

#include <control_msgs/JointControllerState.h>
#include <control_toolbox/pid.h>
#include <ros/duration.h>
#include <ros/time.h>

namespace forward_command_controller
{
namespace internal
{
/// Stamp, set point, measured value, error, period [s], command and the PID's gains.
inline void fillPidState(control_msgs::JointControllerState& msg, const ros::Time& time, double set_point,
                         double process_value, double error, const ros::Duration& period, double command,
                         control_toolbox::Pid& pid)
{
  msg.header.stamp = time;
  msg.set_point = set_point;
  msg.process_value = process_value;
  msg.error = error;
  msg.time_step = period.toSec();
  msg.command = command;
  double dummy = 0.0;
  bool antiwindup = false;
  pid.getGains(msg.p, msg.i, msg.d, msg.i_clamp, dummy, antiwindup);
  msg.antiwindup = antiwindup;
}
}  // namespace internal
}  // namespace forward_command_controller
