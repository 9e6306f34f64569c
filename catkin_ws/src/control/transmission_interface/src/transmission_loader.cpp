// Re-implementation of ros_control's transmission_interface for Debian 12.
#include <transmission_interface/transmission_loader.h>

#include <memory>
#include <vector>

#include <transmission_interface/differential_transmission.h>
#include <transmission_interface/simple_transmission.h>

namespace transmission_interface
{
namespace
{
const char* const SIMPLE = "transmission_interface/SimpleTransmission";
const char* const DIFFERENTIAL = "transmission_interface/DifferentialTransmission";
const char* const FOUR_BAR = "transmission_interface/FourBarLinkageTransmission";

/// Indices of \p items ordered by role (role1 first) when roles are given, else document order.
template <class T>
bool orderByRole(const std::vector<T>& items, const std::string& prefix, std::vector<size_t>& order, std::string& error)
{
  order = { 0, 1 };
  if (items[0].role.empty() && items[1].role.empty())
    return true;
  for (size_t i = 0; i < 2; ++i)
  {
    if (items[i].role == prefix + "1")
      order[0] = i;
    else if (items[i].role == prefix + "2")
      order[1] = i;
    else
    {
      error = "role '" + items[i].role + "' of '" + items[i].name + "' is not " + prefix + "1 or " + prefix + "2";
      return false;
    }
  }
  if (order[0] == order[1])
  {
    error = "both " + prefix + "s have the same role";
    return false;
  }
  return true;
}
}  // namespace

TransmissionSharedPtr loadTransmission(const TransmissionInfo& info, std::string& error)
{
  const std::string where = "Transmission '" + info.name + "' of type '" + info.type + "': ";
  try
  {
    if (info.type == SIMPLE)
    {
      if (info.joints.size() != 1 || info.actuators.size() != 1)
      {
        error = where + "a SimpleTransmission needs exactly one joint and one actuator.";
        return nullptr;
      }
      if (!info.actuators[0].has_mechanical_reduction)
      {
        error = where + "actuator '" + info.actuators[0].name + "' has no <mechanicalReduction>.";
        return nullptr;
      }
      return std::make_shared<SimpleTransmission>(info.actuators[0].mechanical_reduction, info.joints[0].offset);
    }
    if (info.type == DIFFERENTIAL)
    {
      if (info.joints.size() != 2 || info.actuators.size() != 2)
      {
        error = where + "a DifferentialTransmission needs exactly two joints and two actuators.";
        return nullptr;
      }
      std::vector<size_t> jo, ao;
      std::string why;
      if (!orderByRole(info.joints, "joint", jo, why) || !orderByRole(info.actuators, "actuator", ao, why))
      {
        error = where + why + ".";
        return nullptr;
      }
      for (const ActuatorInfo& a : info.actuators)
      {
        if (!a.has_mechanical_reduction)
        {
          error = where + "actuator '" + a.name + "' has no <mechanicalReduction>.";
          return nullptr;
        }
      }
      return std::make_shared<DifferentialTransmission>(
          std::vector<double>{ info.actuators[ao[0]].mechanical_reduction, info.actuators[ao[1]].mechanical_reduction },
          std::vector<double>{ info.joints[jo[0]].mechanical_reduction, info.joints[jo[1]].mechanical_reduction },
          std::vector<double>{ info.joints[jo[0]].offset, info.joints[jo[1]].offset });
    }
    if (info.type == FOUR_BAR)
    {
      error = where +
              "FourBarLinkageTransmission is not implemented in this re-implementation of "
              "transmission_interface (SimpleTransmission and DifferentialTransmission are).";
      return nullptr;
    }
  }
  catch (const TransmissionInterfaceException& e)
  {
    error = where + e.what();
    return nullptr;
  }
  error = where + "unknown transmission type (known: " + SIMPLE + ", " + DIFFERENTIAL + ").";
  return nullptr;
}

}  // namespace transmission_interface
