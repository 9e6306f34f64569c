// Re-implementation of ros_control's transmission_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cassert>

#include <transmission_interface/transmission.h>
#include <transmission_interface/transmission_interface_exception.h>

namespace transmission_interface
{
/**
 * \brief One actuator driving one joint through a reduction n and a joint offset x0:
 *
 * joint effort = n · actuator effort, joint velocity = actuator velocity / n,
 * joint position = actuator position / n + x0 (and the inverses).
 */
class SimpleTransmission : public Transmission
{
public:
  /// Throws TransmissionInterfaceException if \p reduction is zero.
  explicit SimpleTransmission(double reduction, double joint_offset = 0.0)
    : reduction_(reduction), jnt_offset_(joint_offset)
  {
    if (reduction_ == 0.0)
      throw TransmissionInterfaceException("Transmission reduction ratio cannot be zero.");
  }

  void actuatorToJointEffort(const ActuatorData& act, JointData& jnt) override
  {
    check(act.effort.size(), jnt.effort.size());
    *jnt.effort[0] = *act.effort[0] * reduction_;
  }
  void actuatorToJointVelocity(const ActuatorData& act, JointData& jnt) override
  {
    check(act.velocity.size(), jnt.velocity.size());
    *jnt.velocity[0] = *act.velocity[0] / reduction_;
  }
  void actuatorToJointPosition(const ActuatorData& act, JointData& jnt) override
  {
    check(act.position.size(), jnt.position.size());
    *jnt.position[0] = *act.position[0] / reduction_ + jnt_offset_;
  }
  void jointToActuatorEffort(const JointData& jnt, ActuatorData& act) override
  {
    check(act.effort.size(), jnt.effort.size());
    *act.effort[0] = *jnt.effort[0] / reduction_;
  }
  void jointToActuatorVelocity(const JointData& jnt, ActuatorData& act) override
  {
    check(act.velocity.size(), jnt.velocity.size());
    *act.velocity[0] = *jnt.velocity[0] * reduction_;
  }
  void jointToActuatorPosition(const JointData& jnt, ActuatorData& act) override
  {
    check(act.position.size(), jnt.position.size());
    *act.position[0] = (*jnt.position[0] - jnt_offset_) * reduction_;
  }

  std::size_t numActuators() const override { return 1; }
  std::size_t numJoints() const override { return 1; }
  double getActuatorReduction() const { return reduction_; }
  double getJointOffset() const { return jnt_offset_; }

private:
  static void check(std::size_t n_act, std::size_t n_jnt)
  {
    if (n_act != 1 || n_jnt != 1)
      throw TransmissionInterfaceException("SimpleTransmission maps exactly one actuator value to one joint value.");
  }

  double reduction_;
  double jnt_offset_;
};

}  // namespace transmission_interface
