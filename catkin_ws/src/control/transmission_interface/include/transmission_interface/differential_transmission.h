// Re-implementation of ros_control's transmission_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <vector>

#include <transmission_interface/transmission.h>
#include <transmission_interface/transmission_interface_exception.h>

namespace transmission_interface
{
/**
 * \brief Two actuators driving two joints through a differential (e.g. a wrist):
 * actuator reductions n_a1, n_a2, joint reductions n_j1, n_j2, joint offsets x0_1, x0_2.
 *
 * τ_j1 = n_j1 (n_a1 τ_a1 + n_a2 τ_a2), τ_j2 = n_j2 (n_a1 τ_a1 − n_a2 τ_a2);
 * ω_j1 = (ω_a1/n_a1 + ω_a2/n_a2) / (2 n_j1), ω_j2 = (ω_a1/n_a1 − ω_a2/n_a2) / (2 n_j2);
 * positions as velocities plus the joint offsets. The joint→actuator maps are the inverses.
 */
class DifferentialTransmission : public Transmission
{
public:
  DifferentialTransmission(const std::vector<double>& actuator_reduction, const std::vector<double>& joint_reduction,
                           const std::vector<double>& joint_offset = std::vector<double>(2, 0.0))
    : act_reduction_(actuator_reduction), jnt_reduction_(joint_reduction), jnt_offset_(joint_offset)
  {
    if (act_reduction_.size() != 2 || jnt_reduction_.size() != 2 || jnt_offset_.size() != 2)
      throw TransmissionInterfaceException(
          "Reduction and offset vectors of a differential transmission must have size 2.");
    for (double r : act_reduction_)
      if (r == 0.0)
        throw TransmissionInterfaceException("Transmission reduction ratios cannot be zero.");
    for (double r : jnt_reduction_)
      if (r == 0.0)
        throw TransmissionInterfaceException("Transmission reduction ratios cannot be zero.");
  }

  void actuatorToJointEffort(const ActuatorData& act, JointData& jnt) override
  {
    check(act.effort.size(), jnt.effort.size());
    const std::vector<double>& ar = act_reduction_;
    const std::vector<double>& jr = jnt_reduction_;
    *jnt.effort[0] = jr[0] * (*act.effort[0] * ar[0] + *act.effort[1] * ar[1]);
    *jnt.effort[1] = jr[1] * (*act.effort[0] * ar[0] - *act.effort[1] * ar[1]);
  }
  void actuatorToJointVelocity(const ActuatorData& act, JointData& jnt) override
  {
    check(act.velocity.size(), jnt.velocity.size());
    const std::vector<double>& ar = act_reduction_;
    const std::vector<double>& jr = jnt_reduction_;
    *jnt.velocity[0] = (*act.velocity[0] / ar[0] + *act.velocity[1] / ar[1]) / (2.0 * jr[0]);
    *jnt.velocity[1] = (*act.velocity[0] / ar[0] - *act.velocity[1] / ar[1]) / (2.0 * jr[1]);
  }
  void actuatorToJointPosition(const ActuatorData& act, JointData& jnt) override
  {
    check(act.position.size(), jnt.position.size());
    const std::vector<double>& ar = act_reduction_;
    const std::vector<double>& jr = jnt_reduction_;
    *jnt.position[0] = (*act.position[0] / ar[0] + *act.position[1] / ar[1]) / (2.0 * jr[0]) + jnt_offset_[0];
    *jnt.position[1] = (*act.position[0] / ar[0] - *act.position[1] / ar[1]) / (2.0 * jr[1]) + jnt_offset_[1];
  }
  void jointToActuatorEffort(const JointData& jnt, ActuatorData& act) override
  {
    check(act.effort.size(), jnt.effort.size());
    const std::vector<double>& ar = act_reduction_;
    const std::vector<double>& jr = jnt_reduction_;
    *act.effort[0] = (*jnt.effort[0] / jr[0] + *jnt.effort[1] / jr[1]) / (2.0 * ar[0]);
    *act.effort[1] = (*jnt.effort[0] / jr[0] - *jnt.effort[1] / jr[1]) / (2.0 * ar[1]);
  }
  void jointToActuatorVelocity(const JointData& jnt, ActuatorData& act) override
  {
    check(act.velocity.size(), jnt.velocity.size());
    const std::vector<double>& ar = act_reduction_;
    const std::vector<double>& jr = jnt_reduction_;
    *act.velocity[0] = (*jnt.velocity[0] * jr[0] + *jnt.velocity[1] * jr[1]) * ar[0];
    *act.velocity[1] = (*jnt.velocity[0] * jr[0] - *jnt.velocity[1] * jr[1]) * ar[1];
  }
  void jointToActuatorPosition(const JointData& jnt, ActuatorData& act) override
  {
    check(act.position.size(), jnt.position.size());
    const std::vector<double>& ar = act_reduction_;
    const std::vector<double>& jr = jnt_reduction_;
    const double p0 = *jnt.position[0] - jnt_offset_[0];
    const double p1 = *jnt.position[1] - jnt_offset_[1];
    *act.position[0] = (p0 * jr[0] + p1 * jr[1]) * ar[0];
    *act.position[1] = (p0 * jr[0] - p1 * jr[1]) * ar[1];
  }

  std::size_t numActuators() const override { return 2; }
  std::size_t numJoints() const override { return 2; }
  const std::vector<double>& getActuatorReduction() const { return act_reduction_; }
  const std::vector<double>& getJointReduction() const { return jnt_reduction_; }
  const std::vector<double>& getJointOffset() const { return jnt_offset_; }

private:
  static void check(std::size_t n_act, std::size_t n_jnt)
  {
    if (n_act != 2 || n_jnt != 2)
      throw TransmissionInterfaceException(
          "DifferentialTransmission maps exactly two actuator values to two joint values.");
  }

  std::vector<double> act_reduction_;
  std::vector<double> jnt_reduction_;
  std::vector<double> jnt_offset_;
};

}  // namespace transmission_interface
