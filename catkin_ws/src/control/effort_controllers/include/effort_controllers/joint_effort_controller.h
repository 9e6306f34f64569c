// effort_controllers::JointEffortController: forwards `command` (std_msgs/Float64, [N·m or N])
// to one joint's effort (starts at 0).
#pragma once

#include <forward_command_controller/forward_command_controller.h>

namespace effort_controllers
{
typedef forward_command_controller::ForwardCommandController<hardware_interface::EffortJointInterface>
    JointEffortController;
}
