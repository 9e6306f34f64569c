// Re-implementation of ros_control's controller_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <string>

#include <ros/console.h>
#include <ros/node_handle.h>

#include <controller_interface/controller_base.h>
#include <hardware_interface/internal/demangle_symbol.h>
#include <hardware_interface/robot_hw.h>

namespace controller_interface
{
/**
 * \brief Controller using one hardware interface type \p T.
 *
 * Override one of the init() variants; both are called (the first with the controller's
 * NodeHandle only), and both default to true. Resources obtained through claiming
 * interfaces during init are reported as this controller's claims.
 */
template <class T>
class Controller : public virtual ControllerBase
{
public:
  Controller() = default;
  virtual ~Controller() = default;

  /// Initialise with the hardware interface and the controller's NodeHandle.
  virtual bool init(T* /*hw*/, ros::NodeHandle& /*controller_nh*/) { return true; }

  /// Initialise with the hardware interface, the manager's NodeHandle and the controller's.
  virtual bool init(T* /*hw*/, ros::NodeHandle& /*root_nh*/, ros::NodeHandle& /*controller_nh*/) { return true; }

protected:
  bool initRequest(hardware_interface::RobotHW* robot_hw, ros::NodeHandle& root_nh, ros::NodeHandle& controller_nh,
                   ClaimedResources& claimed_resources) override
  {
    if (state_ != ControllerState::CONSTRUCTED)
    {
      ROS_ERROR("Cannot initialize this controller because it failed to be constructed");
      return false;
    }

    T* hw = robot_hw ? robot_hw->get<T>() : nullptr;
    if (!hw)
    {
      ROS_ERROR(
          "This controller requires a hardware interface of type '%s'. "
          "Make sure this is registered in the hardware_interface::RobotHW class.",
          getHardwareInterfaceType().c_str());
      return false;
    }

    hw->clearClaims();
    if (!init(hw, controller_nh) || !init(hw, root_nh, controller_nh))
    {
      ROS_ERROR("Failed to initialize the controller");
      hw->clearClaims();
      return false;
    }
    claimed_resources.assign(1, hardware_interface::InterfaceResources(getHardwareInterfaceType(), hw->getClaims()));
    hw->clearClaims();

    state_ = ControllerState::INITIALIZED;
    return true;
  }

  /// Demangled name of T, e.g. "hardware_interface::VelocityJointInterface".
  std::string getHardwareInterfaceType() const { return hardware_interface::internal::demangledTypeName<T>(); }
};

}  // namespace controller_interface
