// Re-implementation of ros_control's controller_manager (Noetic 0.20 API) for Debian 12.
#include <controller_manager/controller_manager.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <set>

#include <controller_manager/controller_loader.h>
#include <controller_manager_msgs/ControllerState.h>

namespace controller_manager
{
typedef controller_manager_msgs::SwitchController::Request SwitchRequest;

ControllerManager::ControllerManager(hardware_interface::RobotHW* robot_hw, const ros::NodeHandle& nh)
  : robot_hw_(robot_hw), root_nh_(nh), cm_node_(nh, "controller_manager")
{
  try
  {
    controller_loaders_.push_back(std::make_shared<ControllerLoader<controller_interface::ControllerBase>>(
        "controller_interface", "controller_interface::ControllerBase"));
  }
  catch (const std::exception& e)
  {
    ROS_ERROR(
        "Controller manager: cannot create the controller plugin loader (package controller_interface, "
        "base class controller_interface::ControllerBase): %s. Only registered loaders will be used.",
        e.what());
  }

  // Advertise services last: callbacks may come at once.
  srv_list_controllers_ = cm_node_.advertiseService("list_controllers", &ControllerManager::listControllersSrv, this);
  srv_list_controller_types_ =
      cm_node_.advertiseService("list_controller_types", &ControllerManager::listControllerTypesSrv, this);
  srv_load_controller_ = cm_node_.advertiseService("load_controller", &ControllerManager::loadControllerSrv, this);
  srv_unload_controller_ =
      cm_node_.advertiseService("unload_controller", &ControllerManager::unloadControllerSrv, this);
  srv_switch_controller_ =
      cm_node_.advertiseService("switch_controller", &ControllerManager::switchControllerSrv, this);
  srv_reload_libraries_ =
      cm_node_.advertiseService("reload_controller_libraries", &ControllerManager::reloadControllerLibrariesSrv, this);
}

ControllerManager::~ControllerManager()
{
  srv_list_controllers_.shutdown();
  srv_list_controller_types_.shutdown();
  srv_load_controller_.shutdown();
  srv_unload_controller_.shutdown();
  srv_switch_controller_.shutdown();
  srv_reload_libraries_.shutdown();
  std::lock_guard<std::recursive_mutex> guard(controllers_lock_);
  controllers_.clear();  // before the loaders that own their libraries
}

// ------------------------------------------------------------------------------------------ realtime

void ControllerManager::update(const ros::Time& time, const ros::Duration& period, bool reset_controllers)
{
  std::lock_guard<std::recursive_mutex> guard(controllers_lock_);

  if (reset_controllers)
  {
    for (ControllerSpec& spec : controllers_)
    {
      if (!spec.c->isRunning())
        continue;
      try
      {
        spec.c->stopRequest(time);
        spec.c->startRequest(time);
      }
      catch (const std::exception& e)
      {
        abortAfterException(spec, time, "reset", e.what());
      }
      catch (...)
      {
        abortAfterException(spec, time, "reset", "unknown exception");
      }
    }
  }

  for (ControllerSpec& spec : controllers_)
  {
    try
    {
      spec.c->updateRequest(time, period);
    }
    catch (const std::exception& e)
    {
      abortAfterException(spec, time, "update", e.what());
    }
    catch (...)
    {
      abortAfterException(spec, time, "update", "unknown exception");
    }
  }

  if (switch_pending_.load())
  {
    std::lock_guard<std::mutex> switch_guard(switch_lock_);
    if (switch_params_.do_switch)
    {
      if (!switch_params_.started)
      {
        robot_hw_->doSwitch(switch_start_list_, switch_stop_list_);
        switch_params_.started = true;
        switch_params_.init_time = time;  // the timeout runs on the loop's clock
      }
      stopControllers(time);
      if (switch_params_.start_asap)
        startControllersAsap(time);
      else
        startControllers(time);
      if (!switch_params_.do_switch)
      {
        switch_pending_ = false;
        switch_done_.notify_all();
      }
    }
  }
}

void ControllerManager::abortAfterException(ControllerSpec& spec, const ros::Time& time, const char* where,
                                            const char* what)
{
  ROS_ERROR(
      "Controller '%s' (type '%s') threw an exception in %s: %s. The controller is aborted; stop and "
      "start it again, or unload it.",
      spec.info.name.c_str(), spec.info.type.c_str(), where, what);
  try
  {
    spec.c->abortRequest(time);
  }
  catch (...)
  {
    spec.c->state_ = controller_interface::ControllerBase::ControllerState::ABORTED;
  }
}

controller_manager::ControllerSpec* ControllerManager::specOf(controller_interface::ControllerBase* c)
{
  for (ControllerSpec& spec : controllers_)
    if (spec.c.get() == c)
      return &spec;
  return nullptr;
}

bool ControllerManager::safeRequest(controller_interface::ControllerBase* c, const ros::Time& time, Request request)
{
  try
  {
    switch (request)
    {
      case Request::START:
        return c->startRequest(time);
      case Request::STOP:
        return c->stopRequest(time);
      case Request::WAIT:
        return c->waitRequest(time);
      case Request::ABORT:
        return c->abortRequest(time);
    }
  }
  catch (const std::exception& e)
  {
    ControllerSpec* spec = specOf(c);
    if (spec)
      abortAfterException(*spec, time, request == Request::START ? "starting" : "stopping/waiting/aborting", e.what());
  }
  catch (...)
  {
    ControllerSpec* spec = specOf(c);
    if (spec)
      abortAfterException(*spec, time, request == Request::START ? "starting" : "stopping/waiting/aborting",
                          "unknown exception");
  }
  return false;
}

void ControllerManager::stopControllers(const ros::Time& time)
{
  for (controller_interface::ControllerBase* request : stop_request_)
  {
    if (request->isRunning() && !safeRequest(request, time, Request::STOP) && !request->isAborted())
      ROS_FATAL("Failed to stop controller in realtime loop. This should never happen.");
  }
}

void ControllerManager::startControllers(const ros::Time& time)
{
  const hardware_interface::RobotHW::SwitchState result = robot_hw_->switchResult();
  if (result == hardware_interface::RobotHW::SwitchState::DONE)
  {
    for (controller_interface::ControllerBase* request : start_request_)
    {
      if (!safeRequest(request, time, Request::START) && !request->isAborted())
        ROS_FATAL("Failed to start controller in realtime loop. This should never happen.");
    }
    switch_params_.do_switch = false;
  }
  else if (result == hardware_interface::RobotHW::SwitchState::ERROR ||
           (switch_params_.timeout > 0.0 && (time - switch_params_.init_time).toSec() > switch_params_.timeout))
  {
    for (controller_interface::ControllerBase* request : start_request_)
      safeRequest(request, time, Request::ABORT);
    switch_params_.do_switch = false;
  }
  else
  {
    for (controller_interface::ControllerBase* request : start_request_)
      safeRequest(request, time, Request::WAIT);
  }
}

void ControllerManager::startControllersAsap(const ros::Time& time)
{
  for (controller_interface::ControllerBase* request : start_request_)
  {
    if (request->isRunning() || request->isAborted())
      continue;
    for (const ControllerSpec& spec : controllers_)
    {
      if (spec.c.get() != request)
        continue;
      const hardware_interface::RobotHW::SwitchState result = robot_hw_->switchResult(spec.info);
      if (result == hardware_interface::RobotHW::SwitchState::DONE)
        safeRequest(request, time, Request::START);
      else if (result == hardware_interface::RobotHW::SwitchState::ERROR ||
               (switch_params_.timeout > 0.0 && (time - switch_params_.init_time).toSec() > switch_params_.timeout))
        safeRequest(request, time, Request::ABORT);
      else
        safeRequest(request, time, Request::WAIT);
      break;
    }
  }
  if (std::all_of(start_request_.begin(), start_request_.end(),
                  [](controller_interface::ControllerBase* r) { return r->isRunning() || r->isAborted(); }))
    switch_params_.do_switch = false;
}

// -------------------------------------------------------------------------------------- non-realtime

controller_interface::ControllerBase* ControllerManager::getControllerByName(const std::string& name)
{
  std::lock_guard<std::recursive_mutex> guard(controllers_lock_);
  for (const ControllerSpec& spec : controllers_)
  {
    if (spec.info.name == name)
      return spec.c.get();
  }
  return nullptr;
}

void ControllerManager::getControllerNames(std::vector<std::string>& names)
{
  std::lock_guard<std::recursive_mutex> guard(controllers_lock_);
  names.clear();
  for (const ControllerSpec& spec : controllers_)
    names.push_back(spec.info.name);
}

void ControllerManager::clearSwitchRequest()
{
  start_request_.clear();
  stop_request_.clear();
  switch_start_list_.clear();
  switch_stop_list_.clear();
}

/// Drops from the requests what needs no switch (best effort) or fails (strict: false, ERROR),
/// fills switch_start_list_ / switch_stop_list_ and lists the controllers that would run after
/// the switch.
bool ControllerManager::planSwitch(bool strict, std::list<hardware_interface::ControllerInfo>& info_list)
{
  std::lock_guard<std::recursive_mutex> guard(controllers_lock_);
  for (const ControllerSpec& spec : controllers_)
  {
    controller_interface::ControllerBase* c = spec.c.get();
    bool in_stop_list = std::find(stop_request_.begin(), stop_request_.end(), c) != stop_request_.end();
    bool in_start_list = std::find(start_request_.begin(), start_request_.end(), c) != start_request_.end();
    const bool is_running = c->isRunning();

    if (!is_running && in_stop_list)
    {
      if (strict)
      {
        ROS_ERROR_STREAM("Could not stop controller '" << spec.info.name << "' since it is not running");
        return false;
      }
      in_stop_list = false;
      stop_request_.erase(std::remove(stop_request_.begin(), stop_request_.end(), c), stop_request_.end());
    }

    if (is_running && !in_stop_list && in_start_list)
    {
      if (strict)
      {
        ROS_ERROR_STREAM("Controller '" << spec.info.name << "' is already running");
        return false;
      }
      in_start_list = false;
      start_request_.erase(std::remove(start_request_.begin(), start_request_.end(), c), start_request_.end());
    }

    if (is_running && in_stop_list && !in_start_list)
      switch_stop_list_.push_back(spec.info);
    else if (!is_running && !in_stop_list && in_start_list)
      switch_start_list_.push_back(spec.info);

    bool add_to_list = is_running;
    if (in_stop_list)
      add_to_list = false;
    if (in_start_list)
      add_to_list = true;
    if (add_to_list)
      info_list.push_back(spec.info);
  }
  return true;
}

/// The controllers named in `names` (a switch request's start or stop list); a missing one is an
/// ERROR and false when strict, a DEBUG line otherwise.
bool ControllerManager::requestControllers(const std::vector<std::string>& names, bool strict, const char* action,
                                           std::vector<controller_interface::ControllerBase*>& request)
{
  for (const std::string& name : names)
  {
    controller_interface::ControllerBase* ct = getControllerByName(name);
    if (ct)
    {
      request.push_back(ct);
      continue;
    }
    if (strict)
    {
      ROS_ERROR("Could not %s controller with name %s because no controller with this name exists", action,
                name.c_str());
      return false;
    }
    ROS_DEBUG("Could not %s controller with name %s because no controller with this name exists", action, name.c_str());
  }
  return true;
}

bool ControllerManager::switchController(const std::vector<std::string>& start_controllers,
                                         const std::vector<std::string>& stop_controllers, const int strictness_in,
                                         bool start_asap, double timeout)
{
  std::lock_guard<std::recursive_mutex> nonrt(services_lock_);
  int strictness = strictness_in;
  if (strictness == 0)
  {
    ROS_WARN(
        "Controller Manager: To switch controllers you need to specify a strictness level of "
        "controller_manager_msgs::SwitchController::STRICT (%d) or ::BEST_EFFORT (%d). "
        "Defaulting to ::BEST_EFFORT.",
        SwitchRequest::STRICT, SwitchRequest::BEST_EFFORT);
    strictness = SwitchRequest::BEST_EFFORT;
  }
  const bool strict = strictness == SwitchRequest::STRICT;

  // Switches are serialised by services_lock_ and none is pending here, so update() does not
  // read the request lists while they are prepared (switch_lock_ is taken only to hand over:
  // update() holds controllers_lock_ before switch_lock_, never the other way round).
  clearSwitchRequest();
  if (!requestControllers(stop_controllers, strict, "stop", stop_request_) ||
      !requestControllers(start_controllers, strict, "start", start_request_))
  {
    clearSwitchRequest();
    return false;
  }

  // Resource checks on the set of controllers that would be running after the switch.
  std::list<hardware_interface::ControllerInfo> info_list;
  if (!planSwitch(strict, info_list))
  {
    clearSwitchRequest();
    return false;
  }

  if (robot_hw_->checkForConflict(info_list))
  {
    ROS_ERROR("Could not switch controllers, due to resource conflict");
    clearSwitchRequest();
    return false;
  }

  if (!robot_hw_->prepareSwitch(switch_start_list_, switch_stop_list_))
  {
    ROS_ERROR(
        "Could not switch controllers. The hardware interface combination for the requested controllers is "
        "unfeasible.");
    clearSwitchRequest();
    return false;
  }

  if (start_request_.empty() && stop_request_.empty())
  {
    ROS_DEBUG("Nothing to switch");
    return true;
  }

  return waitForSwitch(strictness, start_asap, timeout);
}

/// Hands the prepared switch to update() and waits until it is done (or withdrawn: see
/// switch_wait_timeout_); true when the controllers were switched.
bool ControllerManager::waitForSwitch(int strictness, bool start_asap, double timeout)
{
  std::unique_lock<std::mutex> switch_guard(switch_lock_);
  switch_params_ = SwitchParams();
  switch_params_.strictness = strictness;
  switch_params_.start_asap = start_asap;
  switch_params_.timeout = timeout;
  switch_params_.do_switch = true;
  switch_pending_ = true;

  // update() performs the switch: wait for it, but not forever unless told so (a simulator,
  // whose paused world calls no update(), waits as upstream does)
  ROS_DEBUG("Request atomic controller switch from realtime loop");
  const bool bounded = switch_wait_timeout_ > 0.0;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(switch_wait_timeout_ + std::max(0.0, timeout));
  while (switch_params_.do_switch)
  {
    if (!ros::ok())
      break;
    if (bounded && std::chrono::steady_clock::now() >= deadline)
      break;
    switch_done_.wait_for(switch_guard, std::chrono::milliseconds(10));
  }
  if (switch_params_.do_switch)
  {
    const bool started = switch_params_.started;
    switch_params_.do_switch = false;
    switch_pending_ = false;
    clearSwitchRequest();
    if (!ros::ok())
      return false;
    if (started)
      ROS_ERROR(
          "Controller manager: the controller switch did not complete within %.1f s: the hardware did not "
          "finish switching. Switch withdrawn.",
          switch_wait_timeout_ + std::max(0.0, timeout));
    else
      ROS_ERROR(
          "Controller manager: update() was not called within %.1f s, so the controller switch was withdrawn. "
          "Is the control loop running, in another thread than the one serving the controller_manager "
          "services (e.g. use a ros::AsyncSpinner)?",
          switch_wait_timeout_ + std::max(0.0, timeout));
    return false;
  }
  clearSwitchRequest();
  ROS_DEBUG("Successfully switched controllers");
  return true;
}

}  // namespace controller_manager
