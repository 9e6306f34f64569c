// Re-implementation of ros_control's controller_manager (Noetic 0.20 API) for Debian 12.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <pluginlib/class_loader.hpp>

#include <controller_manager/controller_loader_interface.h>

namespace controller_manager
{
/**
 * \brief Loads controllers of base class \p ControllerType through pluginlib.
 *
 * Plugins are declared by packages that depend on \p package and export
 * `<package plugin="${prefix}/..._plugins.xml"/>` in their package.xml.
 */
template <class ControllerType>
class ControllerLoader : public ControllerLoaderInterface
{
public:
  ControllerLoader(const std::string& package, const std::string& base_class)
    : ControllerLoaderInterface(base_class), package_(package), base_class_(base_class)
  {
    reload();
  }

  controller_interface::ControllerBaseSharedPtr createInstance(const std::string& lookup_name) override
  {
    try
    {
      return controller_interface::ControllerBaseSharedPtr(controller_loader_->createUniqueInstance(lookup_name));
    }
    catch (const pluginlib::PluginlibException& e)
    {
      throw std::runtime_error(e.what());
    }
  }

  std::vector<std::string> getDeclaredClasses() override { return controller_loader_->getDeclaredClasses(); }

  void reload() override
  {
    controller_loader_.reset();  // unload the libraries before re-reading the declarations
    controller_loader_ = std::make_shared<pluginlib::ClassLoader<ControllerType>>(package_, base_class_);
  }

private:
  std::string package_;
  std::string base_class_;
  std::shared_ptr<pluginlib::ClassLoader<ControllerType>> controller_loader_;
};

}  // namespace controller_manager
