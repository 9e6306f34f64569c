// Re-implementation of ros_control's transmission_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace transmission_interface
{
/// Pointers to actuator-space values (one per actuator).
struct ActuatorData
{
  std::vector<double*> position;
  std::vector<double*> velocity;
  std::vector<double*> effort;
  std::vector<double*> absolute_position;
  std::vector<double*> torque_sensor;
};

/// Pointers to joint-space values (one per joint).
struct JointData
{
  std::vector<double*> position;
  std::vector<double*> velocity;
  std::vector<double*> effort;
  std::vector<double*> absolute_position;
  std::vector<double*> torque_sensor;
};

/// Maps efforts, velocities and positions between actuator and joint space.
class Transmission
{
public:
  virtual ~Transmission() = default;

  virtual void actuatorToJointEffort(const ActuatorData& act_data, JointData& jnt_data) = 0;
  virtual void actuatorToJointVelocity(const ActuatorData& act_data, JointData& jnt_data) = 0;
  virtual void actuatorToJointPosition(const ActuatorData& act_data, JointData& jnt_data) = 0;
  virtual void jointToActuatorEffort(const JointData& jnt_data, ActuatorData& act_data) = 0;
  virtual void jointToActuatorVelocity(const JointData& jnt_data, ActuatorData& act_data) = 0;
  virtual void jointToActuatorPosition(const JointData& jnt_data, ActuatorData& act_data) = 0;

  virtual std::size_t numActuators() const = 0;
  virtual std::size_t numJoints() const = 0;
};

typedef std::shared_ptr<Transmission> TransmissionSharedPtr;

}  // namespace transmission_interface
