// Re-implementation of ros_control's transmission_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>
#include <vector>

#include <transmission_interface/transmission_info.h>

namespace tinyxml2
{
class XMLElement;
}

namespace transmission_interface
{
/**
 * \brief Reads the `<transmission>` elements of a URDF.
 *
 * Invalid transmissions (no name, no type, a joint without hardware interface...) are skipped
 * with an ERROR naming the transmission and what is wrong; parse() fails only on an empty or
 * malformed document.
 */
class TransmissionParser
{
public:
  /// \param[out] transmissions the valid transmissions, in document order
  static bool parse(const std::string& urdf_string, std::vector<TransmissionInfo>& transmissions);

protected:
  static bool parseJoints(const tinyxml2::XMLElement* trans_elem, const std::string& transmission_name,
                          std::vector<JointInfo>& joints);
  static bool parseActuators(const tinyxml2::XMLElement* trans_elem, const std::string& transmission_name,
                             std::vector<ActuatorInfo>& actuators);
};

}  // namespace transmission_interface
