#include <gazebo_ros_control/bridge_joint.h>

namespace gazebo_ros_control
{

bool parseJointInterface(const std::string& name, JointInterface* out)
{
  std::string bare = name;
  const std::string::size_type slash = bare.rfind('/');
  if (slash != std::string::npos)
    bare = bare.substr(slash + 1);
  if (bare == "EffortJointInterface")
    *out = JointInterface::EFFORT;
  else if (bare == "VelocityJointInterface")
    *out = JointInterface::VELOCITY;
  else if (bare == "PositionJointInterface")
    *out = JointInterface::POSITION;
  else if (bare == "JointStateInterface")
    *out = JointInterface::STATE;
  else
    return false;
  return true;
}

const char* jointInterfaceName(JointInterface interface)
{
  switch (interface)
  {
    case JointInterface::EFFORT:
      return "EffortJointInterface";
    case JointInterface::VELOCITY:
      return "VelocityJointInterface";
    case JointInterface::POSITION:
      return "PositionJointInterface";
    case JointInterface::STATE:
      break;
  }
  return "JointStateInterface";
}

}  // namespace gazebo_ros_control
