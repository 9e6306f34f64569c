// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <hardware_interface/hardware_interface.h>
#include <hardware_interface/internal/resource_manager.h>

namespace hardware_interface
{
/// Claim policy: getHandle does not mark the resource as used (read-only interfaces).
class DontClaimResources
{
public:
  static void claim(HardwareInterface* /*hw*/, const std::string& /*name*/) {}
};

/// Claim policy: getHandle marks the resource as claimed by the controller being initialised.
class ClaimResources
{
public:
  static void claim(HardwareInterface* hw, const std::string& name) { hw->claim(name); }
};

/**
 * \brief A HardwareInterface that is also a ResourceManager of \p ResourceHandle.
 *
 * getHandle() converts a missing resource into HardwareInterfaceException and applies
 * \p ClaimPolicy (ClaimResources for command interfaces).
 */
template <class ResourceHandle, class ClaimPolicy = DontClaimResources>
class HardwareResourceManager : public HardwareInterface, public ResourceManager<ResourceHandle>
{
public:
  std::vector<std::string> getNames() const { return this->ResourceManager<ResourceHandle>::getNames(); }

  void registerHandle(const ResourceHandle& handle) { this->ResourceManager<ResourceHandle>::registerHandle(handle); }

  ResourceHandle getHandle(const std::string& name)
  {
    try
    {
      ResourceHandle out = this->ResourceManager<ResourceHandle>::getHandle(name);
      ClaimPolicy::claim(this, name);
      return out;
    }
    catch (const std::logic_error& e)
    {
      throw HardwareInterfaceException(e.what());
    }
  }
};

}  // namespace hardware_interface
