// Re-implementation of ros_control's controller_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <memory>
#include <vector>

#include <ros/console.h>
#include <ros/node_handle.h>
#include <ros/time.h>

#include <hardware_interface/interface_resources.h>
#include <hardware_interface/robot_hw.h>

namespace controller_interface
{
/**
 * \brief Abstract controller: the lifecycle the controller manager drives.
 *
 * initRequest (non-realtime) → startRequest → updateRequest every cycle → stopRequest; waiting
 * and aborted are extra states a manager or the controller itself may enter.
 */
class ControllerBase
{
public:
  ControllerBase() = default;
  virtual ~ControllerBase() = default;
  ControllerBase(const ControllerBase&) = delete;
  ControllerBase& operator=(const ControllerBase&) = delete;
  ControllerBase(ControllerBase&&) = delete;
  ControllerBase& operator=(ControllerBase&&) = delete;

  /// Realtime: called just before the first update.
  virtual void starting(const ros::Time& /*time*/) {}
  /// Realtime: called every cycle while running; \p period is the time since the last update [s].
  virtual void update(const ros::Time& time, const ros::Duration& period) = 0;
  /// Realtime: called just after the last update.
  virtual void stopping(const ros::Time& /*time*/) {}
  /// Realtime: called while the controller waits to start.
  virtual void waiting(const ros::Time& /*time*/) {}
  /// Realtime: called when the controller is aborted.
  virtual void aborting(const ros::Time& /*time*/) {}

  bool isInitialized() const { return state_ == ControllerState::INITIALIZED; }
  bool isRunning() const { return state_ == ControllerState::RUNNING; }
  bool isStopped() const { return state_ == ControllerState::STOPPED; }
  bool isWaiting() const { return state_ == ControllerState::WAITING; }
  bool isAborted() const { return state_ == ControllerState::ABORTED; }

  /// Calls update() only when running.
  void updateRequest(const ros::Time& time, const ros::Duration& period)
  {
    if (state_ == ControllerState::RUNNING)
      update(time, period);
  }

  /// Calls starting() and enters RUNNING from any state but CONSTRUCTED.
  bool startRequest(const ros::Time& time)
  {
    if (state_ == ControllerState::CONSTRUCTED)
    {
      ROS_FATAL("Failed to start controller. It is not initialized.");
      return false;
    }
    starting(time);
    state_ = ControllerState::RUNNING;
    return true;
  }

  /// Calls stopping() and enters STOPPED from any state but CONSTRUCTED.
  bool stopRequest(const ros::Time& time)
  {
    if (state_ == ControllerState::CONSTRUCTED)
    {
      ROS_FATAL("Failed to stop controller. It is not initialized.");
      return false;
    }
    stopping(time);
    state_ = ControllerState::STOPPED;
    return true;
  }

  /// Calls waiting() and enters WAITING from any state but CONSTRUCTED.
  bool waitRequest(const ros::Time& time)
  {
    if (state_ == ControllerState::CONSTRUCTED)
    {
      ROS_FATAL("Failed to wait controller. It is not initialized.");
      return false;
    }
    waiting(time);
    state_ = ControllerState::WAITING;
    return true;
  }

  /// Calls aborting() and enters ABORTED from any state but CONSTRUCTED.
  bool abortRequest(const ros::Time& time)
  {
    if (state_ == ControllerState::CONSTRUCTED)
    {
      ROS_FATAL("Failed to abort controller. It is not initialized.");
      return false;
    }
    aborting(time);
    state_ = ControllerState::ABORTED;
    return true;
  }

  typedef std::vector<hardware_interface::InterfaceResources> ClaimedResources;

  /**
   * \brief Non-realtime: initialise the controller on \p robot_hw.
   * \param root_nh the controller manager's namespace (topics, services)
   * \param controller_nh the controller's namespace (its configuration)
   * \param[out] claimed_resources resources claimed, per hardware interface
   */
  virtual bool initRequest(hardware_interface::RobotHW* robot_hw, ros::NodeHandle& root_nh,
                           ros::NodeHandle& controller_nh, ClaimedResources& claimed_resources) = 0;

  enum class ControllerState
  {
    CONSTRUCTED,
    INITIALIZED,
    RUNNING,
    STOPPED,
    WAITING,
    ABORTED
  };

  /// Current execution state.
  ControllerState state_ = ControllerState::CONSTRUCTED;
};

typedef std::shared_ptr<ControllerBase> ControllerBaseSharedPtr;

}  // namespace controller_interface
