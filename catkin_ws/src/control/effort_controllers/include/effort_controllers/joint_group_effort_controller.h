// effort_controllers::JointGroupEffortController: forwards `command`
// (std_msgs/Float64MultiArray) to the efforts of `joints` (starts at 0).
#pragma once

#include <forward_command_controller/forward_joint_group_command_controller.h>

namespace effort_controllers
{
typedef forward_command_controller::ForwardJointGroupCommandController<hardware_interface::EffortJointInterface>
    JointGroupEffortController;
}
