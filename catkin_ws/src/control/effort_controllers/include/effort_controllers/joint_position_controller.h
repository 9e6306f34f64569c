// Re-implementation of effort_controllers/joint_position_controller.h (ros_controllers 0.21):
// PID from a position set point to a joint effort. The code is the template
// forward_command_controller::JointPositionPidController, shared with
// velocity_controllers::JointPositionController.
#pragma once

#include <forward_command_controller/joint_position_pid_controller.h>
#include <hardware_interface/joint_command_interface.h>

namespace effort_controllers
{

/**
 * Parameters (controller namespace): `joint` (required), `pid/{p,i,d,i_clamp,...}` (p required),
 * and `robot_description` found upward from the namespace (joint type and limits).
 * Subscribes `command` (std_msgs/Float64, position [rad or m]); publishes `state`
 * (control_msgs/JointControllerState) every 10th update; the PID output is the joint effort.
 */
class JointPositionController
  : public forward_command_controller::JointPositionPidController<hardware_interface::EffortJointInterface>
{
public:
  using forward_command_controller::JointPositionPidController<
      hardware_interface::EffortJointInterface>::JointPositionPidController;
};

}  // namespace effort_controllers
