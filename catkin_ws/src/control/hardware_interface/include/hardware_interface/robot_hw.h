// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <list>
#include <map>
#include <memory>
#include <string>

#include <ros/console.h>
#include <ros/duration.h>
#include <ros/node_handle.h>
#include <ros/time.h>

#include <hardware_interface/controller_info.h>
#include <hardware_interface/hardware_interface.h>
#include <hardware_interface/internal/interface_manager.h>

namespace hardware_interface
{
/**
 * \brief Robot hardware abstraction: the interfaces it registers, read/write of the hardware,
 * and the hooks the controller manager calls around a controller switch.
 *
 * The control loop is `read(time, period); cm.update(time, period); write(time, period);`.
 * Time is passed in: read() and write() should not query the wall clock.
 */
class RobotHW : public InterfaceManager
{
public:
  virtual ~RobotHW() = default;

  /// Set up interfaces and handles; \p robot_hw_nh holds this hardware's configuration.
  virtual bool init(ros::NodeHandle& /*root_nh*/, ros::NodeHandle& /*robot_hw_nh*/) { return true; }

  /**
   * \brief Whether the given set of controllers (those that would be running after a switch)
   * conflicts. Default: a resource claimed by more than one controller is a conflict.
   */
  virtual bool checkForConflict(const std::list<ControllerInfo>& info) const
  {
    std::map<std::string, std::list<std::string>> claimers;
    for (const ControllerInfo& controller : info)
      for (const InterfaceResources& claimed : controller.claimed_resources)
        for (const std::string& resource : claimed.resources)
          claimers[resource].push_back(controller.name);

    bool in_conflict = false;
    for (const auto& kv : claimers)
    {
      if (kv.second.size() > 1)
      {
        std::string controller_list;
        for (const std::string& name : kv.second)
          controller_list += name + ", ";
        ROS_WARN("Resource conflict on [%s].  Controllers = [%s]", kv.first.c_str(), controller_list.c_str());
        in_conflict = true;
      }
    }
    return in_conflict;
  }

  /// Non-realtime check before a switch; false refuses the switch.
  virtual bool prepareSwitch(const std::list<ControllerInfo>& /*start_list*/,
                             const std::list<ControllerInfo>& /*stop_list*/)
  {
    return true;
  }

  /// Realtime: perform the hardware mode switch for the controllers being started/stopped.
  virtual void doSwitch(const std::list<ControllerInfo>& /*start_list*/, const std::list<ControllerInfo>& /*stop_list*/)
  {
  }

  enum class SwitchState
  {
    DONE,
    ONGOING,
    ERROR
  };

  /// State of the last doSwitch (asynchronous hardware may report ONGOING).
  virtual SwitchState switchResult() const { return SwitchState::DONE; }
  virtual SwitchState switchResult(const ControllerInfo& /*controller*/) const { return SwitchState::DONE; }

  /// Read the hardware state into the registered handles' data.
  virtual void read(const ros::Time& /*time*/, const ros::Duration& /*period*/) {}

  /// Write the registered handles' commands to the hardware.
  virtual void write(const ros::Time& /*time*/, const ros::Duration& /*period*/) {}
};

typedef std::shared_ptr<RobotHW> RobotHWSharedPtr;

}  // namespace hardware_interface
