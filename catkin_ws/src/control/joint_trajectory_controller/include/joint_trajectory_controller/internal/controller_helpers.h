// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
// What JointTrajectoryController's init() and update() hand off (joint_trajectory_controller_impl.h):
// the robot description, the joint handles, the state message, a goal's success.
#pragma once

#include <string>
#include <vector>

#include <hardware_interface/hardware_interface_exception.h>
#include <hardware_interface/internal/demangle_symbol.h>
#include <ros/console.h>
#include <ros/names.h>
#include <ros/node_handle.h>
#include <ros/param.h>
#include <urdf/model.h>

#include <joint_trajectory_controller/joint_trajectory_segment.h>

namespace joint_trajectory_controller
{
namespace internal
{
inline std::string controllerName(const ros::NodeHandle& nh)
{
  const std::string& ns = nh.getNamespace();
  const std::size_t slash = ns.find_last_of('/');
  return slash == std::string::npos ? ns : ns.substr(slash + 1);
}

/// Stamp and desired/actual/error of a state message (the action feedback or the state topic's).
template <class Msg, class State>
void fillStateMsg(Msg& m, const ros::Time& time, const State& desired, const State& actual, const State& error)
{
  m.header.stamp = time;
  m.desired.positions = desired.position;
  m.desired.velocities = desired.velocity;
  m.desired.accelerations = desired.acceleration;
  m.actual.positions = actual.position;
  m.actual.velocities = actual.velocity;
  m.error.positions = error.position;
  m.error.velocities = error.velocity;
}

/// The robot description, as the original looks it up: in the controller manager's namespace,
/// else the nearest 'robot_description' above it; false with an ERROR when there is none.
inline bool robotDescription(const ros::NodeHandle& root_nh, const std::string& name, std::string& urdf_string,
                             std::string& urdf_param)
{
  urdf_param = root_nh.resolveName("robot_description");
  if (root_nh.getParam("robot_description", urdf_string))
    return true;
  // As the original's fallback to the global description: search up the namespaces.
  if (!root_nh.searchParam("robot_description", urdf_param))
    urdf_param = ros::names::resolve("robot_description");
  if (ros::param::get(urdf_param, urdf_string))
    return true;
  ROS_ERROR_STREAM_NAMED(name, "Could not find the robot description in parameter '"
                                   << root_nh.resolveName("robot_description") << "' nor '" << urdf_param << "'.");
  return false;
}

/// The controller's joint handles, and which joints are continuous in the URDF (they wrap
/// around); false with an ERROR naming the joint when the URDF or the interface lacks it.
template <class HardwareInterface>
bool jointHandles(HardwareInterface* hw, const urdf::Model& urdf, const std::vector<std::string>& joint_names,
                  const std::string& name, std::vector<bool>& angle_wraparound,
                  std::vector<typename HardwareInterface::ResourceHandleType>& joints)
{
  const unsigned int n_joints = joint_names.size();
  angle_wraparound.assign(n_joints, false);
  joints.resize(n_joints);
  for (unsigned int i = 0; i < n_joints; ++i)
  {
    const auto urdf_joint = urdf.getJoint(joint_names[i]);
    if (!urdf_joint)
    {
      ROS_ERROR_STREAM_NAMED(name, "Could not find joint '" << joint_names[i] << "' in URDF model.");
      return false;
    }
    angle_wraparound[i] = urdf_joint->type == urdf::Joint::CONTINUOUS;
    try
    {
      joints[i] = hw->getHandle(joint_names[i]);
    }
    catch (const hardware_interface::HardwareInterfaceException& e)
    {
      ROS_ERROR_STREAM_NAMED(name, "Could not find joint '"
                                       << joint_names[i] << "' in '"
                                       << hardware_interface::internal::demangledTypeName<HardwareInterface>()
                                       << "': " << e.what());
      return false;
    }
  }
  return true;
}

/// The state topic's message with the joints' names and zeroed desired / actual / error.
template <class Msg>
void resetStateMsg(Msg& m, const std::vector<std::string>& joint_names)
{
  const std::size_t n_joints = joint_names.size();
  m.joint_names = joint_names;
  m.desired.positions.assign(n_joints, 0.0);
  m.desired.velocities.assign(n_joints, 0.0);
  m.desired.accelerations.assign(n_joints, 0.0);
  m.actual.positions.assign(n_joints, 0.0);
  m.actual.velocities.assign(n_joints, 0.0);
  m.error.positions.assign(n_joints, 0.0);
  m.error.velocities.assign(n_joints, 0.0);
}

/// ~state_publish_rate and ~action_monitor_rate [Hz] (defaults 50 and 20); false with an ERROR
/// unless both are positive.
inline bool publishRates(const ros::NodeHandle& nh, const std::string& name, double& state_publish_rate,
                         double& action_monitor_rate)
{
  nh.param("state_publish_rate", state_publish_rate, 50.0);
  nh.param("action_monitor_rate", action_monitor_rate, 20.0);
  if (state_publish_rate > 0.0 && action_monitor_rate > 0.0)
    return true;
  ROS_ERROR_STREAM_NAMED(name, "state_publish_rate and action_monitor_rate must be positive (got "
                                   << state_publish_rate << " and " << action_monitor_rate << ").");
  return false;
}

/// Succeeds the goal once every joint it moves has reached its goal tolerance.
inline void succeedIfDone(GoalTracker& goal, unsigned int n_joints)
{
  bool done = true;
  for (unsigned int i = 0; i < n_joints; ++i)
    done = done && (!goal.joints()[i] || goal.successful()[i]);
  if (done)
    goal.requestSucceeded();
}
}  // namespace internal
}  // namespace joint_trajectory_controller
