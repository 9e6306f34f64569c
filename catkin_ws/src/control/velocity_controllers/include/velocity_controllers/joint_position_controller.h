// Re-implementation of velocity_controllers/joint_position_controller.h (ros_controllers 0.21):
// PID from a position set point to a joint velocity. The code is the template
// forward_command_controller::JointPositionPidController, shared with
// effort_controllers::JointPositionController.
#pragma once

#include <forward_command_controller/joint_position_pid_controller.h>
#include <hardware_interface/joint_command_interface.h>

namespace velocity_controllers
{

/**
 * Parameters (controller namespace): `joint` (required), `pid/{p,i,d,i_clamp,...}` (p required),
 * and `robot_description` found upward from the namespace (joint type and limits).
 * Subscribes `command` (std_msgs/Float64, position [rad or m]); publishes `state`
 * (control_msgs/JointControllerState) every 10th update; the PID output is the joint velocity.
 */
class JointPositionController
  : public forward_command_controller::JointPositionPidController<hardware_interface::VelocityJointInterface>
{
public:
  using forward_command_controller::JointPositionPidController<
      hardware_interface::VelocityJointInterface>::JointPositionPidController;
};

}  // namespace velocity_controllers
