// position_controllers::JointGroupPositionController: forwards `command`
// (std_msgs/Float64MultiArray) to the positions of `joints` (starts holding the current ones).
#pragma once

#include <forward_command_controller/forward_joint_group_command_controller.h>

namespace position_controllers
{
typedef forward_command_controller::ForwardJointGroupCommandController<hardware_interface::PositionJointInterface>
    JointGroupPositionController;
}
