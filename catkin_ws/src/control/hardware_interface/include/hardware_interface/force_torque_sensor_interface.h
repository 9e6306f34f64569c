// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>

#include <hardware_interface/internal/hardware_resource_manager.h>

namespace hardware_interface
{
/// Read-only view of a force-torque sensor: force [N] and torque [N·m], 3 values each (may be null).
class ForceTorqueSensorHandle
{
public:
  ForceTorqueSensorHandle() = default;
  ForceTorqueSensorHandle(const std::string& name, const std::string& frame_id, const double* force,
                          const double* torque)
    : name_(name), frame_id_(frame_id), force_(force), torque_(torque)
  {
  }

  std::string getName() const { return name_; }
  std::string getFrameId() const { return frame_id_; }
  const double* getForce() const { return force_; }
  const double* getTorque() const { return torque_; }

private:
  std::string name_;
  std::string frame_id_;
  const double* force_ = nullptr;
  const double* torque_ = nullptr;
};

/// Read-only force-torque sensors (no claims).
class ForceTorqueSensorInterface : public HardwareResourceManager<ForceTorqueSensorHandle>
{
};

}  // namespace hardware_interface
