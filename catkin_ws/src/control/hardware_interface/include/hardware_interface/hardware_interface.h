// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <set>
#include <string>

#include <hardware_interface/hardware_interface_exception.h>

namespace hardware_interface
{
/// Base of every hardware interface: records which resources a controller claimed during init.
class HardwareInterface
{
public:
  virtual ~HardwareInterface() = default;

  /// Record that the resource \p resource is claimed (called by getHandle of claiming interfaces).
  virtual void claim(const std::string& resource) { claims_.insert(resource); }
  void clearClaims() { claims_.clear(); }
  std::set<std::string> getClaims() const { return claims_; }

protected:
  std::set<std::string> claims_;
};

}  // namespace hardware_interface
