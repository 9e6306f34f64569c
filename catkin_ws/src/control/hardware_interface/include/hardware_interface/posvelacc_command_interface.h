// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cassert>
#include <string>

#include <hardware_interface/internal/hardware_resource_manager.h>
#include <hardware_interface/posvel_command_interface.h>

namespace hardware_interface
{
/// A joint state plus position [rad or m], velocity [rad/s or m/s] and acceleration [rad/s² or m/s²]
/// commands.
class PosVelAccJointHandle : public PosVelJointHandle
{
public:
  PosVelAccJointHandle() = default;

  /// Throws HardwareInterfaceException if a command pointer is null.
  PosVelAccJointHandle(const JointStateHandle& js, double* cmd_pos, double* cmd_vel, double* cmd_acc)
    : PosVelJointHandle(js, cmd_pos, cmd_vel), cmd_acc_(cmd_acc)
  {
    if (!cmd_acc_)
      throw HardwareInterfaceException("Cannot create handle '" + js.getName() +
                                       "'. Command acceleration data pointer is null.");
  }

  using PosVelJointHandle::setCommand;
  void setCommand(double cmd_pos, double cmd_vel, double cmd_acc)
  {
    setCommandPosition(cmd_pos);
    setCommandVelocity(cmd_vel);
    setCommandAcceleration(cmd_acc);
  }
  void setCommandAcceleration(double cmd_acc)
  {
    assert(cmd_acc_);
    *cmd_acc_ = cmd_acc;
  }
  double getCommandAcceleration() const
  {
    assert(cmd_acc_);
    return *cmd_acc_;
  }

private:
  double* cmd_acc_ = nullptr;
};

/// Position + velocity + acceleration commands; getHandle claims the joint.
class PosVelAccJointInterface : public HardwareResourceManager<PosVelAccJointHandle, ClaimResources>
{
};

}  // namespace hardware_interface
