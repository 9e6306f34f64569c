// position_controllers::JointPositionController: forwards `command` (std_msgs/Float64,
// [rad or m]) to one joint's position command (starts holding the current position).
#pragma once

#include <forward_command_controller/forward_command_controller.h>

namespace position_controllers
{
typedef forward_command_controller::ForwardCommandController<hardware_interface::PositionJointInterface>
    JointPositionController;
}
