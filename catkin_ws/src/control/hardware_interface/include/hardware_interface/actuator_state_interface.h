// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cassert>
#include <string>

#include <hardware_interface/hardware_interface_exception.h>
#include <hardware_interface/internal/hardware_resource_manager.h>

namespace hardware_interface
{
/// Read-only view of one actuator: position, velocity and effort (actuator space).
class ActuatorStateHandle
{
public:
  ActuatorStateHandle() = default;

  ActuatorStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff)
    : name_(name), pos_(pos), vel_(vel), eff_(eff)
  {
    if (!pos)
      throw HardwareInterfaceException("Cannot create handle '" + name + "'. Position data pointer is null.");
    if (!vel)
      throw HardwareInterfaceException("Cannot create handle '" + name + "'. Velocity data pointer is null.");
    if (!eff)
      throw HardwareInterfaceException("Cannot create handle '" + name + "'. Effort data pointer is null.");
  }

  std::string getName() const { return name_; }
  double getPosition() const
  {
    assert(pos_);
    return *pos_;
  }
  double getVelocity() const
  {
    assert(vel_);
    return *vel_;
  }
  double getEffort() const
  {
    assert(eff_);
    return *eff_;
  }
  const double* getPositionPtr() const { return pos_; }
  const double* getVelocityPtr() const { return vel_; }
  const double* getEffortPtr() const { return eff_; }

private:
  std::string name_;
  const double* pos_ = nullptr;
  const double* vel_ = nullptr;
  const double* eff_ = nullptr;
};

/// Read-only actuator states (no claims).
class ActuatorStateInterface : public HardwareResourceManager<ActuatorStateHandle>
{
};

}  // namespace hardware_interface
