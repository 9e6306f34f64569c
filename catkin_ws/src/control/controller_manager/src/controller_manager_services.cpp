// Re-implementation of ros_control's controller_manager (Noetic 0.20 API) for Debian 12:
// ControllerManager's loading and unloading of controllers and its ROS services (load, unload,
// switch, list, list types, reload libraries). The realtime loop and the switch are in
// controller_manager.cpp.
#include <controller_manager/controller_manager.h>

#include <algorithm>
#include <exception>

#include <controller_manager_msgs/ControllerState.h>

namespace controller_manager
{
typedef controller_manager_msgs::SwitchController::Request SwitchRequest;

// -------------------------------------------------------------------------------------- non-realtime

void ControllerManager::registerControllerLoader(ControllerLoaderInterfaceSharedPtr controller_loader)
{
  std::lock_guard<std::recursive_mutex> nonrt(services_lock_);
  controller_loaders_.push_back(controller_loader);
}

bool ControllerManager::loadController(const std::string& name)
{
  ROS_DEBUG("Will load controller '%s'", name.c_str());
  std::lock_guard<std::recursive_mutex> nonrt(services_lock_);

  if (getControllerByName(name))
  {
    ROS_ERROR("A controller named '%s' was already loaded inside the controller manager", name.c_str());
    return false;
  }

  ros::NodeHandle c_nh;
  try
  {
    c_nh = ros::NodeHandle(root_nh_, name);
  }
  catch (const std::exception& e)
  {
    ROS_ERROR("Exception thrown while constructing nodehandle for controller with name '%s':\n%s", name.c_str(),
              e.what());
    return false;
  }

  std::string type;
  if (!c_nh.getParam("type", type))
  {
    ROS_ERROR(
        "Could not load controller '%s' because the type was not specified. Did you load the controller "
        "configuration on the parameter server (namespace: '%s')?",
        name.c_str(), c_nh.getNamespace().c_str());
    return false;
  }

  ROS_DEBUG("Constructing controller '%s' of type '%s'", name.c_str(), type.c_str());
  controller_interface::ControllerBaseSharedPtr c = createController(type);
  if (!c)
  {
    ROS_ERROR("Could not load controller '%s' because controller type '%s' does not exist.", name.c_str(),
              type.c_str());
    ROS_ERROR("Use 'rosservice call controller_manager/list_controller_types' to get the available types");
    return false;
  }

  ROS_DEBUG("Initializing controller '%s'", name.c_str());
  controller_interface::ControllerBase::ClaimedResources claimed_resources;
  if (!initController(*c, name, c_nh, claimed_resources))
  {
    ROS_ERROR("Initializing controller '%s' failed", name.c_str());
    return false;
  }

  ControllerSpec spec;
  spec.info.name = name;
  spec.info.type = type;
  spec.info.claimed_resources = claimed_resources;
  spec.c = c;
  {
    std::lock_guard<std::recursive_mutex> guard(controllers_lock_);
    controllers_.push_back(spec);
  }
  ROS_DEBUG("Successfully load controller '%s'", name.c_str());
  return true;
}

controller_interface::ControllerBaseSharedPtr ControllerManager::createController(const std::string& type)
{
  controller_interface::ControllerBaseSharedPtr c;
  try
  {
    for (auto it = controller_loaders_.begin(); !c && it != controller_loaders_.end(); ++it)
    {
      const std::vector<std::string> types = (*it)->getDeclaredClasses();
      if (std::find(types.begin(), types.end(), type) != types.end())
        c = (*it)->createInstance(type);
    }
  }
  catch (const std::exception& e)
  {
    ROS_ERROR("Could not load class %s: %s", type.c_str(), e.what());
  }
  return c;
}

bool ControllerManager::initController(controller_interface::ControllerBase& c, const std::string& name,
                                       ros::NodeHandle& c_nh,
                                       controller_interface::ControllerBase::ClaimedResources& claimed_resources)
{
  try
  {
    return c.initRequest(robot_hw_, root_nh_, c_nh, claimed_resources);
  }
  catch (const std::exception& e)
  {
    ROS_ERROR("Exception thrown while initializing controller %s.\n%s", name.c_str(), e.what());
  }
  catch (...)
  {
    ROS_ERROR("Exception thrown while initializing controller %s", name.c_str());
  }
  return false;
}

bool ControllerManager::unloadController(const std::string& name)
{
  ROS_DEBUG("Will unload controller '%s'", name.c_str());
  std::lock_guard<std::recursive_mutex> nonrt(services_lock_);

  ControllerSpec removed;
  {
    std::lock_guard<std::recursive_mutex> guard(controllers_lock_);
    auto it = std::find_if(controllers_.begin(), controllers_.end(),
                           [&name](const ControllerSpec& spec) { return spec.info.name == name; });
    if (it == controllers_.end())
    {
      ROS_ERROR("Could not unload controller with name %s because no controller with this name exists", name.c_str());
      return false;
    }
    if (it->c->isRunning())
    {
      ROS_ERROR("Could not unload controller with name %s because it is still running", name.c_str());
      return false;
    }
    removed = *it;
    controllers_.erase(it);
  }
  removed.c.reset();  // destroyed here, outside the realtime lock
  ROS_DEBUG("Successfully unloaded controller '%s'", name.c_str());
  return true;
}

// ------------------------------------------------------------------------------------------ services

bool ControllerManager::reloadControllerLibrariesSrv(controller_manager_msgs::ReloadControllerLibraries::Request& req,
                                                     controller_manager_msgs::ReloadControllerLibraries::Response& resp)
{
  std::lock_guard<std::recursive_mutex> nonrt(services_lock_);

  std::vector<std::string> controllers;
  getControllerNames(controllers);
  if (!controllers.empty() && !req.force_kill)
  {
    ROS_ERROR("Controller manager: Cannot reload controller libraries because there are still %i controllers running",
              static_cast<int>(controllers.size()));
    resp.ok = false;
    return true;
  }

  if (!controllers.empty())
  {
    ROS_INFO("Controller manager: Killing all running controllers");
    std::vector<std::string> running;
    for (const std::string& name : controllers)
    {
      controller_interface::ControllerBase* c = getControllerByName(name);
      if (c && c->isRunning())
        running.push_back(name);
    }
    if (!running.empty() && !switchController({}, running, SwitchRequest::BEST_EFFORT))
    {
      ROS_ERROR("Controller manager: Cannot reload controller libraries because failed to stop running controllers");
      resp.ok = false;
      return true;
    }
    for (const std::string& name : controllers)
    {
      if (!unloadController(name))
      {
        ROS_ERROR("Controller manager: Cannot reload controller libraries because failed to unload controller %s",
                  name.c_str());
        resp.ok = false;
        return true;
      }
    }
  }

  for (ControllerLoaderInterfaceSharedPtr& loader : controller_loaders_)
  {
    try
    {
      loader->reload();
      ROS_INFO("Controller manager: reloaded controller libraries for %s", loader->getName().c_str());
    }
    catch (const std::exception& e)
    {
      ROS_ERROR("Controller manager: reloading controller libraries for %s failed: %s", loader->getName().c_str(),
                e.what());
      resp.ok = false;
      return true;
    }
  }
  resp.ok = true;
  return true;
}

bool ControllerManager::listControllerTypesSrv(controller_manager_msgs::ListControllerTypes::Request& /*req*/,
                                               controller_manager_msgs::ListControllerTypes::Response& resp)
{
  std::lock_guard<std::recursive_mutex> nonrt(services_lock_);
  for (ControllerLoaderInterfaceSharedPtr& loader : controller_loaders_)
  {
    for (const std::string& type : loader->getDeclaredClasses())
    {
      resp.types.push_back(type);
      resp.base_classes.push_back(loader->getName());
    }
  }
  return true;
}

static std::string stateName(const controller_interface::ControllerBase& c)
{
  typedef controller_interface::ControllerBase::ControllerState State;
  switch (c.state_)
  {
    case State::INITIALIZED:
      return "initialized";
    case State::RUNNING:
      return "running";
    case State::STOPPED:
      return "stopped";
    case State::WAITING:
      return "waiting";
    case State::ABORTED:
      return "aborted";
    default:
      return "unknown";
  }
}

bool ControllerManager::listControllersSrv(controller_manager_msgs::ListControllers::Request& /*req*/,
                                           controller_manager_msgs::ListControllers::Response& resp)
{
  std::lock_guard<std::recursive_mutex> nonrt(services_lock_);
  std::lock_guard<std::recursive_mutex> guard(controllers_lock_);
  resp.controller.resize(controllers_.size());
  for (size_t i = 0; i < controllers_.size(); ++i)
  {
    controller_manager_msgs::ControllerState& cs = resp.controller[i];
    cs.name = controllers_[i].info.name;
    cs.type = controllers_[i].info.type;
    cs.state = stateName(*controllers_[i].c);
    for (const hardware_interface::InterfaceResources& res : controllers_[i].info.claimed_resources)
    {
      controller_manager_msgs::HardwareInterfaceResources iface_res;
      iface_res.hardware_interface = res.hardware_interface;
      iface_res.resources.assign(res.resources.begin(), res.resources.end());
      cs.claimed_resources.push_back(iface_res);
    }
  }
  return true;
}

bool ControllerManager::loadControllerSrv(controller_manager_msgs::LoadController::Request& req,
                                          controller_manager_msgs::LoadController::Response& resp)
{
  ROS_DEBUG("loading service called for controller %s ", req.name.c_str());
  resp.ok = loadController(req.name);
  return true;
}

bool ControllerManager::unloadControllerSrv(controller_manager_msgs::UnloadController::Request& req,
                                            controller_manager_msgs::UnloadController::Response& resp)
{
  ROS_DEBUG("unloading service called for controller %s ", req.name.c_str());
  resp.ok = unloadController(req.name);
  return true;
}

bool ControllerManager::switchControllerSrv(controller_manager_msgs::SwitchController::Request& req,
                                            controller_manager_msgs::SwitchController::Response& resp)
{
  ROS_DEBUG("switching service called");
  resp.ok = switchController(req.start_controllers, req.stop_controllers, req.strictness, req.start_asap, req.timeout);
  return true;
}

}  // namespace controller_manager
