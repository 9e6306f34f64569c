// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cassert>
#include <stdexcept>
#include <string>

#include <hardware_interface/hardware_interface_exception.h>
#include <hardware_interface/internal/hardware_resource_manager.h>

namespace hardware_interface
{
/**
 * \brief Read-only view of one joint: pointers to position [rad or m], velocity [rad/s or m/s]
 * and effort [N·m or N], optionally an absolute encoder position and a torque sensor value.
 *
 * Constructors throw HardwareInterfaceException on a null data pointer.
 */
class JointStateHandle
{
public:
  JointStateHandle() = default;

  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff)
    : name_(name), pos_(pos), vel_(vel), eff_(eff)
  {
    checkBasePointers();
  }

  /// With an absolute encoder position.
  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff,
                   const double* absolute_pos)
    : JointStateHandle(name, pos, vel, eff)
  {
    if (!absolute_pos)
      throw HardwareInterfaceException("Cannot create handle '" + name +
                                       "'. Absolute encoder position data pointer is null.");
    absolute_pos_ = absolute_pos;
  }

  /// With an absolute encoder position and a torque sensor.
  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff,
                   const double* absolute_pos, const double* torque_sensor)
    : JointStateHandle(name, pos, vel, eff, absolute_pos)
  {
    if (!torque_sensor)
      throw HardwareInterfaceException("Cannot create handle '" + name + "'. Torque sensor data pointer is null.");
    torque_sensor_ = torque_sensor;
  }

  /// With a torque sensor only (the trailing bool only selects this overload).
  JointStateHandle(const std::string& name, const double* pos, const double* vel, const double* eff,
                   const double* torque_sensor, bool /*unused*/)
    : JointStateHandle(name, pos, vel, eff)
  {
    if (!torque_sensor)
      throw HardwareInterfaceException("Cannot create handle '" + name + "'. Torque sensor data pointer is null.");
    torque_sensor_ = torque_sensor;
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

  double getAbsolutePosition() const
  {
    if (!hasAbsolutePosition())
      throw std::runtime_error("Joint state handle does not contain absolute encoder position information");
    return *absolute_pos_;
  }

  double getTorqueSensor() const
  {
    if (!hasTorqueSensor())
      throw std::runtime_error("Joint state handle does not contain torque sensor information");
    return *torque_sensor_;
  }

  const double* getPositionPtr() const { return pos_; }
  const double* getVelocityPtr() const { return vel_; }
  const double* getEffortPtr() const { return eff_; }
  const double* getAbsolutePositionPtr() const
  {
    if (!hasAbsolutePosition())
      throw std::runtime_error("Joint state handle does not contain absolute encoder position information");
    return absolute_pos_;
  }
  const double* getTorqueSensorPtr() const
  {
    if (!hasTorqueSensor())
      throw std::runtime_error("Joint state handle does not contain torque sensor information");
    return torque_sensor_;
  }

  bool hasAbsolutePosition() const { return absolute_pos_ != nullptr; }
  bool hasTorqueSensor() const { return torque_sensor_ != nullptr; }

private:
  void checkBasePointers() const
  {
    if (!pos_)
      throw HardwareInterfaceException("Cannot create handle '" + name_ + "'. Position data pointer is null.");
    if (!vel_)
      throw HardwareInterfaceException("Cannot create handle '" + name_ + "'. Velocity data pointer is null.");
    if (!eff_)
      throw HardwareInterfaceException("Cannot create handle '" + name_ + "'. Effort data pointer is null.");
  }

  std::string name_;
  const double* pos_ = nullptr;
  const double* vel_ = nullptr;
  const double* eff_ = nullptr;
  const double* absolute_pos_ = nullptr;
  const double* torque_sensor_ = nullptr;
};

/// Read-only joint states; getHandle does not claim, so any number of controllers may share it.
class JointStateInterface : public HardwareResourceManager<JointStateHandle>
{
};

}  // namespace hardware_interface
