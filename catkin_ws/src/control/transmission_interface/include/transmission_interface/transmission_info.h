// Re-implementation of ros_control's transmission_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>
#include <vector>

namespace transmission_interface
{
/// A `<joint>` of a URDF `<transmission>`.
struct JointInfo
{
  std::string name;
  std::vector<std::string> hardware_interfaces;  ///< e.g. "hardware_interface/EffortJointInterface"
  std::string role;                              ///< optional `<role>` (differential, four-bar)
  std::string xml_element;                       ///< the `<joint>` element as XML text
  double offset = 0.0;                           ///< optional `<offset>` [rad or m] (extension)
  double mechanical_reduction = 1.0;             ///< optional `<mechanicalReduction>` (extension)
};

/// An `<actuator>` of a URDF `<transmission>`.
struct ActuatorInfo
{
  std::string name;
  std::vector<std::string> hardware_interfaces;  ///< optional (legacy)
  std::string role;                              ///< optional `<role>` (extension: differential)
  std::string xml_element;                       ///< the `<actuator>` element as XML text
  double mechanical_reduction = 1.0;             ///< `<mechanicalReduction>` (extension; 1 if absent)
  bool has_mechanical_reduction = false;         ///< whether `<mechanicalReduction>` was given
};

/// One URDF `<transmission>`.
struct TransmissionInfo
{
  std::string name;
  std::string type;  ///< e.g. "transmission_interface/SimpleTransmission"
  std::vector<JointInfo> joints;
  std::vector<ActuatorInfo> actuators;
};

}  // namespace transmission_interface
