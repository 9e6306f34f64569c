// Re-implementation of ros_control's controller_manager (Noetic 0.20 API) for Debian 12.
#pragma once

#include <atomic>
#include <condition_variable>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>

#include <controller_interface/controller_base.h>
#include <controller_manager/controller_loader_interface.h>
#include <controller_manager/controller_spec.h>
#include <controller_manager_msgs/ListControllerTypes.h>
#include <controller_manager_msgs/ListControllers.h>
#include <controller_manager_msgs/LoadController.h>
#include <controller_manager_msgs/ReloadControllerLibraries.h>
#include <controller_manager_msgs/SwitchController.h>
#include <controller_manager_msgs/UnloadController.h>
#include <hardware_interface/robot_hw.h>

namespace controller_manager
{
/**
 * \brief Loads, unloads, starts and stops controllers on a RobotHW and runs them.
 *
 * The control loop calls update() periodically: `robot_hw.read(); cm.update(time, period);
 * robot_hw.write();`. Services under `<nh>/controller_manager/`: list_controllers,
 * list_controller_types, load_controller, unload_controller, switch_controller,
 * reload_controller_libraries.
 *
 * A switch is prepared in the caller's thread and carried out by the next update(); the caller
 * (a service callback too) waits for it. The loop must therefore run in another thread than
 * the callback queue serving the services (e.g. a ros::AsyncSpinner). If update() does not
 * complete a requested switch within the switch wait bound (30 s wall time, plus the request's
 * timeout), the request is withdrawn with an error instead of blocking the caller forever.
 */
class ControllerManager
{
public:
  ControllerManager(hardware_interface::RobotHW* robot_hw, const ros::NodeHandle& nh = ros::NodeHandle());
  virtual ~ControllerManager();

  /**
   * \brief Realtime: run the controllers and perform a pending switch.
   * \param reset_controllers stop and restart every running controller first (e.g. after
   * the motors were re-enabled)
   */
  void update(const ros::Time& time, const ros::Duration& period, bool reset_controllers = false);

  /// Load controller \p name: its type is read from `<nh>/<name>/type`.
  bool loadController(const std::string& name);

  /// Unload a controller that is not running.
  bool unloadController(const std::string& name);

  /**
   * \brief Stop \p stop_controllers and start \p start_controllers in one update cycle.
   * \param strictness controller_manager_msgs::SwitchController::Request::STRICT fails the whole
   * switch on any error, BEST_EFFORT skips what cannot be done (0 = BEST_EFFORT with a warning)
   * \param start_asap start each controller as soon as the hardware is ready for it
   * \param timeout [s, controller time] how long to wait for the hardware switch; 0 = no limit
   */
  bool switchController(const std::vector<std::string>& start_controllers,
                        const std::vector<std::string>& stop_controllers, const int strictness, bool start_asap = false,
                        double timeout = 0.0);

  /// The controller named \p name, nullptr if none is loaded.
  virtual controller_interface::ControllerBase* getControllerByName(const std::string& name);

  /// Add a loader that is asked (after the default pluginlib one) to create controllers.
  void registerControllerLoader(ControllerLoaderInterfaceSharedPtr controller_loader);

  /// Names of the loaded controllers.
  void getControllerNames(std::vector<std::string>& v);

  /// Wall-time bound for a caller's wait on a switch (default 30 s); 0 or less: wait while
  /// ros::ok(), as upstream (gazebo_ros_control: a paused world calls no update()).
  void setSwitchWaitTimeout(double seconds) { switch_wait_timeout_ = seconds; }

protected:
  bool listControllerTypesSrv(controller_manager_msgs::ListControllerTypes::Request& req,
                              controller_manager_msgs::ListControllerTypes::Response& resp);
  bool listControllersSrv(controller_manager_msgs::ListControllers::Request& req,
                          controller_manager_msgs::ListControllers::Response& resp);
  bool switchControllerSrv(controller_manager_msgs::SwitchController::Request& req,
                           controller_manager_msgs::SwitchController::Response& resp);
  bool loadControllerSrv(controller_manager_msgs::LoadController::Request& req,
                         controller_manager_msgs::LoadController::Response& resp);
  bool unloadControllerSrv(controller_manager_msgs::UnloadController::Request& req,
                           controller_manager_msgs::UnloadController::Response& resp);
  bool reloadControllerLibrariesSrv(controller_manager_msgs::ReloadControllerLibraries::Request& req,
                                    controller_manager_msgs::ReloadControllerLibraries::Response& resp);

  hardware_interface::RobotHW* robot_hw_;
  ros::NodeHandle root_nh_, cm_node_;

  /// The loaders (declared before the controllers: they must outlive them).
  std::list<ControllerLoaderInterfaceSharedPtr> controller_loaders_;

  /// Loaded controllers; guarded by controllers_lock_ (update() holds it for one cycle).
  std::vector<ControllerSpec> controllers_;
  std::recursive_mutex controllers_lock_;

  /// Pending switch, guarded by switch_lock_.
  struct SwitchParams
  {
    bool do_switch = false;
    bool started = false;
    ros::Time init_time;
    int strictness = 0;
    bool start_asap = false;
    double timeout = 0.0;
  };
  SwitchParams switch_params_;
  std::vector<controller_interface::ControllerBase*> start_request_, stop_request_;
  std::list<hardware_interface::ControllerInfo> switch_start_list_, switch_stop_list_;
  std::mutex switch_lock_;
  std::condition_variable switch_done_;
  std::atomic<bool> switch_pending_{ false };
  double switch_wait_timeout_ = 30.0;

  /// Serialises the service callbacks (and the public non-realtime API).
  std::recursive_mutex services_lock_;

  ros::ServiceServer srv_list_controllers_, srv_list_controller_types_, srv_load_controller_;
  ros::ServiceServer srv_unload_controller_, srv_switch_controller_, srv_reload_libraries_;

private:
  enum class Request
  {
    START,
    STOP,
    WAIT,
    ABORT
  };
  /// Realtime: a lifecycle request that cannot crash the loop (a throwing controller is aborted).
  bool safeRequest(controller_interface::ControllerBase* c, const ros::Time& time, Request request);
  void abortAfterException(ControllerSpec& spec, const ros::Time& time, const char* where, const char* what);
  ControllerSpec* specOf(controller_interface::ControllerBase* c);
  void stopControllers(const ros::Time& time);
  void startControllers(const ros::Time& time);
  void startControllersAsap(const ros::Time& time);
  void clearSwitchRequest();
  controller_interface::ControllerBaseSharedPtr createController(const std::string& type);
  bool initController(controller_interface::ControllerBase& c, const std::string& name, ros::NodeHandle& c_nh,
                      controller_interface::ControllerBase::ClaimedResources& claimed_resources);
  bool requestControllers(const std::vector<std::string>& names, bool strict, const char* action,
                          std::vector<controller_interface::ControllerBase*>& request);
  bool planSwitch(bool strict, std::list<hardware_interface::ControllerInfo>& info_list);
  bool waitForSwitch(int strictness, bool start_asap, double timeout);
};

}  // namespace controller_manager
