// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cassert>
#include <string>

#include <hardware_interface/internal/hardware_resource_manager.h>
#include <hardware_interface/joint_state_interface.h>

namespace hardware_interface
{
/// A joint state plus a command (its meaning is given by the interface it is registered in).
class JointHandle : public JointStateHandle
{
public:
  JointHandle() = default;

  /// Throws HardwareInterfaceException if \p cmd is null.
  JointHandle(const JointStateHandle& js, double* cmd) : JointStateHandle(js), cmd_(cmd)
  {
    if (!cmd_)
      throw HardwareInterfaceException("Cannot create handle '" + js.getName() + "'. Command data pointer is null.");
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
  const double* getCommandPtr() const
  {
    assert(cmd_);
    return cmd_;
  }

private:
  double* cmd_ = nullptr;
};

/// Joint commands; getHandle claims the joint for the controller being initialised.
class JointCommandInterface : public HardwareResourceManager<JointHandle, ClaimResources>
{
};

/// Commands are efforts [N·m or N].
class EffortJointInterface : public JointCommandInterface
{
};

/// Commands are velocities [rad/s or m/s].
class VelocityJointInterface : public JointCommandInterface
{
};

/// Commands are positions [rad or m].
class PositionJointInterface : public JointCommandInterface
{
};

}  // namespace hardware_interface
