// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>
#include <vector>

#include <hardware_interface/interface_resources.h>

namespace hardware_interface
{
/// A controller's name, type and the resources it claimed at init.
struct ControllerInfo
{
  std::string name;
  std::string type;
  std::vector<InterfaceResources> claimed_resources;
};

}  // namespace hardware_interface
