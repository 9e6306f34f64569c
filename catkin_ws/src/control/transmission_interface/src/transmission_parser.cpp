// Re-implementation of ros_control's transmission_interface (Noetic 0.20 API) for Debian 12.
#include <transmission_interface/transmission_parser.h>

#include <cstdlib>

#include <ros/console.h>
#include <tinyxml2.h>

namespace transmission_interface
{
namespace
{
std::string toXml(const tinyxml2::XMLElement* elem)
{
  tinyxml2::XMLPrinter printer;
  elem->Accept(&printer);
  return printer.CStr();
}

std::string childText(const tinyxml2::XMLElement* elem, const char* child)
{
  const tinyxml2::XMLElement* c = elem->FirstChildElement(child);
  if (!c || !c->GetText())
    return "";
  std::string s = c->GetText();
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

/// Parse the optional numeric child \p child of \p elem into \p value; false if present but not a number.
bool optionalNumber(const tinyxml2::XMLElement* elem, const char* child, double& value, bool& present)
{
  present = false;
  if (!elem->FirstChildElement(child))
    return true;
  const std::string text = childText(elem, child);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0')
    return false;
  value = v;
  present = true;
  return true;
}

std::vector<std::string> hardwareInterfaces(const tinyxml2::XMLElement* elem)
{
  std::vector<std::string> out;
  for (const tinyxml2::XMLElement* hw = elem->FirstChildElement("hardwareInterface"); hw;
       hw = hw->NextSiblingElement("hardwareInterface"))
  {
    const std::string name = hw->GetText() ? hw->GetText() : "";
    const auto b = name.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
    {
      ROS_WARN_STREAM_NAMED("parser", "Skipping empty hardware interface element in '"
                                          << elem->Name() << "' "
                                          << (elem->Attribute("name") ? elem->Attribute("name") : "") << "'.");
      continue;
    }
    out.push_back(name.substr(b, name.find_last_not_of(" \t\r\n") - b + 1));
  }
  return out;
}
}  // namespace

bool TransmissionParser::parse(const std::string& urdf_string, std::vector<TransmissionInfo>& transmissions)
{
  if (urdf_string.empty())
  {
    ROS_ERROR_STREAM_NAMED("parser", "URDF string is empty.");
    return false;
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf_string.c_str()) != tinyxml2::XML_SUCCESS)
  {
    ROS_ERROR_STREAM_NAMED("parser", "Can't parse transmissions. Invalid robot description: " << doc.ErrorStr());
    return false;
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "robot")
  {
    ROS_ERROR_STREAM_NAMED("parser", "Can't parse transmissions. The robot description has no <robot> root element.");
    return false;
  }

  for (const tinyxml2::XMLElement* trans = root->FirstChildElement("transmission"); trans;
       trans = trans->NextSiblingElement("transmission"))
  {
    TransmissionInfo info;
    info.name = trans->Attribute("name") ? trans->Attribute("name") : "";
    if (info.name.empty())
    {
      ROS_ERROR_STREAM_NAMED("parser", "Empty name attribute specified for transmission.");
      continue;
    }
    if (!trans->FirstChildElement("type"))
    {
      ROS_ERROR_STREAM_NAMED("parser", "No type element found in transmission '" << info.name << "'.");
      continue;
    }
    info.type = childText(trans, "type");
    if (info.type.empty())
    {
      ROS_ERROR_STREAM_NAMED("parser", "Skipping empty type element in transmission '" << info.name << "'.");
      continue;
    }
    if (!parseJoints(trans, info.name, info.joints))
    {
      ROS_ERROR_STREAM_NAMED("parser", "Failed to load joints for transmission '" << info.name << "'.");
      continue;
    }
    if (!parseActuators(trans, info.name, info.actuators))
    {
      ROS_ERROR_STREAM_NAMED("parser", "Failed to load actuators for transmission '" << info.name << "'.");
      continue;
    }
    transmissions.push_back(info);
  }
  if (transmissions.empty())
    ROS_DEBUG_STREAM_NAMED("parser", "No valid transmissions found.");
  return true;
}

bool TransmissionParser::parseJoints(const tinyxml2::XMLElement* trans_elem, const std::string& transmission_name,
                                     std::vector<JointInfo>& joints)
{
  const tinyxml2::XMLElement* joint_elem = trans_elem->FirstChildElement("joint");
  if (!joint_elem)
  {
    ROS_ERROR_STREAM_NAMED("parser", "Transmission '" << transmission_name << "' does not specify any joint.");
    return false;
  }
  for (; joint_elem; joint_elem = joint_elem->NextSiblingElement("joint"))
  {
    JointInfo joint;
    joint.name = joint_elem->Attribute("name") ? joint_elem->Attribute("name") : "";
    if (joint.name.empty())
    {
      ROS_ERROR_STREAM_NAMED("parser",
                             "Empty name attribute specified for joint in transmission '" << transmission_name << "'.");
      continue;
    }
    joint.role = childText(joint_elem, "role");
    joint.hardware_interfaces = hardwareInterfaces(joint_elem);
    if (joint.hardware_interfaces.empty())
    {
      ROS_ERROR_STREAM_NAMED("parser", "No valid hardware interface element found in joint '"
                                           << joint.name << "' of transmission '" << transmission_name << "'.");
      continue;
    }
    bool present = false;
    if (!optionalNumber(joint_elem, "offset", joint.offset, present))
    {
      ROS_ERROR_STREAM_NAMED("parser", "Joint '" << joint.name << "' of transmission '" << transmission_name
                                                 << "': <offset> is not a number.");
      continue;
    }
    if (!optionalNumber(joint_elem, "mechanicalReduction", joint.mechanical_reduction, present))
    {
      ROS_ERROR_STREAM_NAMED("parser", "Joint '" << joint.name << "' of transmission '" << transmission_name
                                                 << "': <mechanicalReduction> is not a number.");
      continue;
    }
    joint.xml_element = toXml(joint_elem);
    joints.push_back(joint);
  }
  if (joints.empty())
  {
    ROS_DEBUG_NAMED("parser", "No valid joint element found.");
    return false;
  }
  return true;
}

bool TransmissionParser::parseActuators(const tinyxml2::XMLElement* trans_elem, const std::string& transmission_name,
                                        std::vector<ActuatorInfo>& actuators)
{
  const tinyxml2::XMLElement* act_elem = trans_elem->FirstChildElement("actuator");
  if (!act_elem)
  {
    ROS_ERROR_STREAM_NAMED("parser", "Transmission '" << transmission_name << "' does not specify any actuator.");
    return false;
  }
  for (; act_elem; act_elem = act_elem->NextSiblingElement("actuator"))
  {
    ActuatorInfo actuator;
    actuator.name = act_elem->Attribute("name") ? act_elem->Attribute("name") : "";
    if (actuator.name.empty())
    {
      ROS_ERROR_STREAM_NAMED(
          "parser", "Empty name attribute specified for actuator in transmission '" << transmission_name << "'.");
      continue;
    }
    actuator.role = childText(act_elem, "role");
    actuator.hardware_interfaces = hardwareInterfaces(act_elem);  // optional (legacy)
    if (!optionalNumber(act_elem, "mechanicalReduction", actuator.mechanical_reduction,
                        actuator.has_mechanical_reduction))
    {
      ROS_ERROR_STREAM_NAMED("parser", "Actuator '" << actuator.name << "' of transmission '" << transmission_name
                                                    << "': <mechanicalReduction> is not a number.");
      continue;
    }
    actuator.xml_element = toXml(act_elem);
    actuators.push_back(actuator);
  }
  if (actuators.empty())
  {
    ROS_DEBUG_NAMED("parser", "No valid actuator element found.");
    return false;
  }
  return true;
}

}  // namespace transmission_interface
