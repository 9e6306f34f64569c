// Re-implementation of ros_control's controller_manager (Noetic 0.20 API) for Debian 12.
#pragma once

#include <controller_interface/controller_base.h>
#include <hardware_interface/controller_info.h>

namespace controller_manager
{
/// A loaded controller: its info (name, type, claimed resources) and the instance.
struct ControllerSpec
{
  hardware_interface::ControllerInfo info;
  controller_interface::ControllerBaseSharedPtr c;
};

}  // namespace controller_manager
