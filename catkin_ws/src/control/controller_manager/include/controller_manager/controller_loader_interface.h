// Re-implementation of ros_control's controller_manager (Noetic 0.20 API) for Debian 12.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <controller_interface/controller_base.h>

namespace controller_manager
{
/// Creates controllers by type name; the manager asks every registered loader in turn.
class ControllerLoaderInterface
{
public:
  explicit ControllerLoaderInterface(const std::string& name) : name_(name) {}
  virtual ~ControllerLoaderInterface() = default;

  /// A new controller of type \p lookup_name; throws std::runtime_error if it cannot be created.
  virtual controller_interface::ControllerBaseSharedPtr createInstance(const std::string& lookup_name) = 0;
  /// The type names this loader can create.
  virtual std::vector<std::string> getDeclaredClasses() = 0;
  /// Forget loaded libraries and re-read the plugin declarations.
  virtual void reload() = 0;
  /// Name of the base class this loader creates (reported by list_controller_types).
  const std::string& getName() const { return name_; }

private:
  std::string name_;
};

typedef std::shared_ptr<ControllerLoaderInterface> ControllerLoaderInterfaceSharedPtr;

}  // namespace controller_manager
