// Re-implementation of ros_control's transmission_interface for Debian 12.
#pragma once

#include <string>

#include <transmission_interface/transmission.h>
#include <transmission_interface/transmission_info.h>

namespace transmission_interface
{
/**
 * \brief Build the Transmission described by \p info (our replacement of upstream's loader
 * plugins). Supported types: transmission_interface/SimpleTransmission (one joint, one actuator,
 * the actuator's `<mechanicalReduction>` is required, the joint's `<offset>` optional) and
 * transmission_interface/DifferentialTransmission (two of each; joint `<role>` joint1/joint2 and
 * actuator `<role>` actuator1/actuator2 order them when given).
 * transmission_interface/FourBarLinkageTransmission and unknown types are refused.
 * \return nullptr with \p error set (one line naming the transmission) on failure
 */
TransmissionSharedPtr loadTransmission(const TransmissionInfo& info, std::string& error);

}  // namespace transmission_interface
