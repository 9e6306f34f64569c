#include <gazebo_ros_control/bridge_model.h>

#include <limits>
#include <sstream>
#include <utility>

namespace gazebo_ros_control
{

BridgeModel::BridgeModel(std::vector<BridgeJoint> joints)
  : joints_(std::move(joints))
  , position_(joints_.size(), 0.0)
  , velocity_(joints_.size(), 0.0)
  , effort_(joints_.size(), 0.0)
  , command_(joints_.size(), std::numeric_limits<double>::quiet_NaN())
  , index_(joints_.size(), 0)
{
}

bool BridgeModel::setState(const std::vector<std::string>& names, const std::vector<double>& position,
                           const std::vector<double>& velocity, const std::vector<double>& effort, std::string* error)
{
  if (names != last_names_)
  {
    std::vector<std::size_t> index(joints_.size(), 0);
    for (std::size_t j = 0; j < joints_.size(); ++j)
    {
      std::size_t k = 0;
      while (k < names.size() && names[k] != joints_[j].name)
        ++k;
      if (k == names.size())
      {
        if (error)
          *error = "joint '" + joints_[j].name + "' is missing from the joint state";
        return false;
      }
      index[j] = k;
    }
    index_ = std::move(index);
    last_names_ = names;
  }
  if (position.size() < names.size() || (!velocity.empty() && velocity.size() < names.size()) ||
      (!effort.empty() && effort.size() < names.size()))
  {
    if (error)
    {
      std::ostringstream s;
      s << "joint state arrays are shorter than its " << names.size() << " names (position " << position.size()
        << ", velocity " << velocity.size() << ", effort " << effort.size() << ")";
      *error = s.str();
    }
    last_names_.clear();
    return false;
  }
  for (std::size_t j = 0; j < joints_.size(); ++j)
  {
    const std::size_t k = index_[j];
    position_[j] = position[k];
    velocity_[j] = velocity.empty() ? 0.0 : velocity[k];
    effort_[j] = effort.empty() ? 0.0 : effort[k];
  }
  return true;
}

void BridgeModel::setState(const double* position, const double* velocity, const double* effort)
{
  for (std::size_t j = 0; j < joints_.size(); ++j)
  {
    position_[j] = position[j];
    velocity_[j] = velocity[j];
    effort_[j] = effort[j];
  }
}

}  // namespace gazebo_ros_control
