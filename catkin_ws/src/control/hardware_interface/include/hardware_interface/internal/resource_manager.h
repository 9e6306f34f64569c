// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <ros/console.h>

#include <hardware_interface/internal/demangle_symbol.h>

namespace hardware_interface
{
/// Non-template base so that interface managers can own resource managers of any handle type.
class ResourceManagerBase
{
public:
  virtual ~ResourceManagerBase() = default;
};

/**
 * \brief Named handles of one type (sorted by name).
 *
 * Registering a name twice replaces the earlier handle with a warning; asking for a name that is
 * not registered throws std::logic_error "Could not find resource '<name>' in '<manager type>'.".
 */
template <class ResourceHandle>
class ResourceManager : public ResourceManagerBase
{
public:
  typedef ResourceHandle ResourceHandleType;

  std::vector<std::string> getNames() const
  {
    std::vector<std::string> out;
    out.reserve(resource_map_.size());
    for (const auto& kv : resource_map_)
      out.push_back(kv.first);
    return out;
  }

  void registerHandle(const ResourceHandle& handle)
  {
    auto it = resource_map_.find(handle.getName());
    if (it == resource_map_.end())
    {
      resource_map_.insert(std::make_pair(handle.getName(), handle));
    }
    else
    {
      ROS_WARN_STREAM("Replacing previously registered handle '" << handle.getName() << "' in '"
                                                                 << internal::demangledTypeName(*this) << "'.");
      it->second = handle;
    }
  }

  ResourceHandle getHandle(const std::string& name)
  {
    auto it = resource_map_.find(name);
    if (it == resource_map_.end())
      throw std::logic_error("Could not find resource '" + name + "' in '" + internal::demangledTypeName(*this) + "'.");
    return it->second;
  }

  /// Fill \p result with the union of the handles of \p managers (used to combine sub-managers).
  template <class T>
  static void concatManagers(std::vector<T*>& managers, T* result)
  {
    for (T* manager : managers)
    {
      for (const std::string& name : manager->getNames())
        result->registerHandle(manager->getHandle(name));
    }
  }

protected:
  typedef std::map<std::string, ResourceHandle> ResourceMap;
  ResourceMap resource_map_;
};

}  // namespace hardware_interface
