// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <ros/console.h>

#include <hardware_interface/internal/demangle_symbol.h>
#include <hardware_interface/internal/resource_manager.h>

namespace hardware_interface
{
namespace internal
{
/// Detects whether T is a ResourceManager (has a ResourceHandleType typedef and getNames()).
template <class T, class = void>
struct CheckIsResourceManager
{
  static constexpr bool value = false;
  static void callGetResources(std::vector<std::string>& /*resources*/, T* /*iface*/) {}
  static T* newCI(std::vector<std::shared_ptr<ResourceManagerBase>>& /*guards*/) { return nullptr; }
  static void callConcatManagers(std::vector<T*>& /*managers*/, T* /*result*/) {}
};

template <class T>
struct CheckIsResourceManager<T, std::void_t<typename T::ResourceHandleType>>
{
  static constexpr bool value = true;
  static void callGetResources(std::vector<std::string>& resources, T* iface) { resources = iface->getNames(); }
  /// New empty interface of type T, owned by \p guards.
  static T* newCI(std::vector<std::shared_ptr<ResourceManagerBase>>& guards)
  {
    auto iface = std::make_shared<T>();
    guards.push_back(iface);
    return iface.get();
  }
  static void callConcatManagers(std::vector<T*>& managers, T* result)
  {
    ResourceManager<typename T::ResourceHandleType>::concatManagers(managers, result);
  }
};

}  // namespace internal

/**
 * \brief Registry of hardware interfaces keyed by their demangled type name.
 *
 * Interfaces registered here and in registered sub-managers (see registerInterfaceManager) are
 * combined by get<T>(): if several interfaces of type T exist, a new T holding all their handles
 * is built (and cached until the number of interfaces changes).
 */
class InterfaceManager
{
public:
  virtual ~InterfaceManager() = default;

  /// Register \p iface (not owned). A second interface of the same type replaces the first.
  template <class T>
  void registerInterface(T* iface)
  {
    const std::string iface_name = internal::demangledTypeName<T>();
    if (interfaces_.find(iface_name) != interfaces_.end())
      ROS_WARN_STREAM("Replacing previously registered interface '" << iface_name << "'.");
    interfaces_[iface_name] = iface;
    internal::CheckIsResourceManager<T>::callGetResources(resources_[iface_name], iface);
  }

  /// Register another manager (e.g. the RobotHW of one part of a combined robot).
  void registerInterfaceManager(InterfaceManager* iface_man) { interface_managers_.push_back(iface_man); }

  /// The interface of type T, nullptr if none is registered here or in sub-managers.
  template <class T>
  T* get()
  {
    const std::string type_name = internal::demangledTypeName<T>();
    std::vector<T*> iface_list;

    auto it = interfaces_.find(type_name);
    if (it != interfaces_.end())
    {
      T* iface = static_cast<T*>(it->second);
      if (!iface)
      {
        ROS_ERROR_STREAM("Failed reconstructing type T = '" << type_name << "'. This should never happen");
        return nullptr;
      }
      iface_list.push_back(iface);
    }
    for (InterfaceManager* manager : interface_managers_)
    {
      T* iface = manager->get<T>();
      if (iface)
        iface_list.push_back(iface);
    }

    if (iface_list.empty())
      return nullptr;
    if (iface_list.size() == 1)
      return iface_list.front();

    auto combo = interfaces_combo_.find(type_name);
    if (combo != interfaces_combo_.end() && num_ifaces_registered_[type_name] == iface_list.size())
      return static_cast<T*>(combo->second);

    T* iface_combo = internal::CheckIsResourceManager<T>::newCI(interface_destruction_list_);
    if (!iface_combo)
    {
      ROS_ERROR(
          "You cannot register multiple interfaces of the same type which are not of type ResourceManager. "
          "There is no established protocol for combining them.");
      return nullptr;
    }
    internal::CheckIsResourceManager<T>::callConcatManagers(iface_list, iface_combo);
    interfaces_combo_[type_name] = iface_combo;
    num_ifaces_registered_[type_name] = iface_list.size();
    return iface_combo;
  }

  /// Demangled type names of the interfaces registered here and in sub-managers.
  std::vector<std::string> getNames() const
  {
    std::vector<std::string> out;
    for (const auto& kv : interfaces_)
      out.push_back(kv.first);
    for (const InterfaceManager* manager : interface_managers_)
    {
      for (const std::string& name : manager->getNames())
        out.push_back(name);
    }
    return out;
  }

  /// Resource names of the interface type \p iface_type (as registered), also from sub-managers.
  std::vector<std::string> getInterfaceResources(const std::string& iface_type) const
  {
    std::vector<std::string> out;
    auto it = resources_.find(iface_type);
    if (it != resources_.end())
      out = it->second;
    for (const InterfaceManager* manager : interface_managers_)
    {
      for (const std::string& name : manager->getInterfaceResources(iface_type))
        out.push_back(name);
    }
    return out;
  }

protected:
  typedef std::map<std::string, void*> InterfaceMap;
  typedef std::vector<InterfaceManager*> InterfaceManagerVector;
  typedef std::map<std::string, size_t> SizeMap;
  typedef std::map<std::string, std::vector<std::string>> ResourceMap;

  InterfaceMap interfaces_;
  InterfaceMap interfaces_combo_;
  InterfaceManagerVector interface_managers_;
  SizeMap num_ifaces_registered_;
  std::vector<std::shared_ptr<ResourceManagerBase>> interface_destruction_list_;
  ResourceMap resources_;
};

}  // namespace hardware_interface
