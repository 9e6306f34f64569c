// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cassert>
#include <string>

#include <hardware_interface/actuator_state_interface.h>
#include <hardware_interface/internal/hardware_resource_manager.h>

namespace hardware_interface
{
/// An actuator state plus a command.
class ActuatorHandle : public ActuatorStateHandle
{
public:
  ActuatorHandle() = default;

  /// Throws HardwareInterfaceException if \p cmd is null.
  ActuatorHandle(const ActuatorStateHandle& as, double* cmd) : ActuatorStateHandle(as), cmd_(cmd)
  {
    if (!cmd_)
      throw HardwareInterfaceException("Cannot create handle '" + as.getName() + "'. Command data pointer is null.");
  }

  void setCommand(double command)
  {
    assert(cmd_);
    *cmd_ = command;
  }
  double getCommand() const
  {
    assert(cmd_);
    return *cmd_;
  }
  double* getCommandPtr() { return cmd_; }

private:
  double* cmd_ = nullptr;
};

/// Actuator commands (any meaning; see the derived interfaces). As the original, getHandle does not
/// claim: actuators are reached through transmissions, joints are what controllers claim.
class ActuatorCommandInterface : public HardwareResourceManager<ActuatorHandle>
{
};

class EffortActuatorInterface : public ActuatorCommandInterface
{
};

class VelocityActuatorInterface : public ActuatorCommandInterface
{
};

class PositionActuatorInterface : public ActuatorCommandInterface
{
};

}  // namespace hardware_interface
