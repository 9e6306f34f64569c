// velocity_controllers::JointGroupVelocityController: forwards `command`
// (std_msgs/Float64MultiArray) to the velocities of `joints` (starts at 0).
#pragma once

#include <forward_command_controller/forward_joint_group_command_controller.h>

namespace velocity_controllers
{
typedef forward_command_controller::ForwardJointGroupCommandController<hardware_interface::VelocityJointInterface>
    JointGroupVelocityController;
}
