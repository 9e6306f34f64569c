// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <set>
#include <string>

namespace hardware_interface
{
/// The resources of one hardware interface type that a controller claims.
struct InterfaceResources
{
  InterfaceResources() = default;
  InterfaceResources(const std::string& hw_iface, const std::set<std::string>& res)
    : hardware_interface(hw_iface), resources(res)
  {
  }

  /// Demangled type name of the hardware interface, e.g. "hardware_interface::EffortJointInterface".
  std::string hardware_interface;
  std::set<std::string> resources;
};

}  // namespace hardware_interface
