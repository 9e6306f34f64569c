// Re-implementation of ros_control's controller_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>
#include <vector>

#include <ros/console.h>
#include <ros/node_handle.h>

#include <controller_interface/controller_base.h>
#include <hardware_interface/internal/demangle_symbol.h>
#include <hardware_interface/robot_hw.h>

namespace controller_interface
{
/**
 * \brief Controller using several hardware interface types \p Interfaces... at once.
 *
 * init() receives a RobotHW that contains only the requested interfaces. With
 * \p allow_optional_interfaces, missing interfaces are not an error (get<T>() returns nullptr).
 * Claims are reported per interface type.
 */
template <class... Interfaces>
class MultiInterfaceController : public virtual ControllerBase
{
  static_assert(sizeof...(Interfaces) > 0, "MultiInterfaceController needs at least one hardware interface type");

public:
  explicit MultiInterfaceController(bool allow_optional_interfaces = false)
    : allow_optional_interfaces_(allow_optional_interfaces)
  {
  }
  virtual ~MultiInterfaceController() = default;

  virtual bool init(hardware_interface::RobotHW* /*robot_hw*/, ros::NodeHandle& /*controller_nh*/) { return true; }
  virtual bool init(hardware_interface::RobotHW* /*robot_hw*/, ros::NodeHandle& /*root_nh*/,
                    ros::NodeHandle& /*controller_nh*/)
  {
    return true;
  }

protected:
  bool initRequest(hardware_interface::RobotHW* robot_hw, ros::NodeHandle& root_nh, ros::NodeHandle& controller_nh,
                   ClaimedResources& claimed_resources) override
  {
    if (state_ != ControllerState::CONSTRUCTED)
    {
      ROS_ERROR("Cannot initialize this controller because it failed to be constructed");
      return false;
    }
    if (!robot_hw)
    {
      ROS_ERROR("Cannot initialize this controller: the RobotHW pointer is null");
      return false;
    }

    std::vector<std::string> missing;
    (checkInterface<Interfaces>(robot_hw, missing), ...);
    if (!missing.empty() && !allow_optional_interfaces_)
    {
      std::string list;
      for (const std::string& name : missing)
        list += (list.empty() ? "" : ", ") + name;
      ROS_ERROR(
          "This controller requires the hardware interface(s) [%s]. "
          "Make sure they are registered in the hardware_interface::RobotHW class.",
          list.c_str());
      return false;
    }

    (populateInterface<Interfaces>(robot_hw), ...);
    (clearClaims<Interfaces>(), ...);
    if (!init(&robot_hw_ctrl_, controller_nh) || !init(&robot_hw_ctrl_, root_nh, controller_nh))
    {
      ROS_ERROR("Failed to initialize the controller");
      (clearClaims<Interfaces>(), ...);
      return false;
    }
    claimed_resources.clear();
    (extractResources<Interfaces>(claimed_resources), ...);
    (clearClaims<Interfaces>(), ...);

    state_ = ControllerState::INITIALIZED;
    return true;
  }

  /// Demangled names of all requested interface types.
  static std::vector<std::string> getHardwareInterfaceTypes()
  {
    return { hardware_interface::internal::demangledTypeName<Interfaces>()... };
  }

  /// The RobotHW given to init(): only the requested interfaces of the real one.
  hardware_interface::RobotHW robot_hw_ctrl_;
  bool allow_optional_interfaces_;

private:
  template <class T>
  static void checkInterface(hardware_interface::RobotHW* robot_hw, std::vector<std::string>& missing)
  {
    if (!robot_hw->get<T>())
      missing.push_back(hardware_interface::internal::demangledTypeName<T>());
  }

  template <class T>
  void populateInterface(hardware_interface::RobotHW* robot_hw)
  {
    T* iface = robot_hw->get<T>();
    if (iface)
      robot_hw_ctrl_.registerInterface(iface);
  }

  template <class T>
  void clearClaims()
  {
    T* iface = robot_hw_ctrl_.get<T>();
    if (iface)
      iface->clearClaims();
  }

  template <class T>
  void extractResources(ClaimedResources& claimed_resources)
  {
    T* iface = robot_hw_ctrl_.get<T>();
    if (iface)
      claimed_resources.emplace_back(hardware_interface::internal::demangledTypeName<T>(), iface->getClaims());
  }
};

}  // namespace controller_interface
