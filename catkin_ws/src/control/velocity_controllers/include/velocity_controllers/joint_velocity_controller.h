// velocity_controllers::JointVelocityController: forwards `command` (std_msgs/Float64,
// [rad/s or m/s]) to one joint's velocity command (starts at 0).
#pragma once

#include <forward_command_controller/forward_command_controller.h>

namespace velocity_controllers
{
typedef forward_command_controller::ForwardCommandController<hardware_interface::VelocityJointInterface>
    JointVelocityController;
}
