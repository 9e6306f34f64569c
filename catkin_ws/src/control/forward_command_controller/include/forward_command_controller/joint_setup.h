// What the init() of every joint controller in forward_command_controller, effort_controllers,
// velocity_controllers and position_controllers reads and checks, written once: the `joint` /
// `joints` parameters, the joint handles and a group command's size and values (urdf_joint.h:
// the position PID controllers' URDF joint). Not part of the original's API: the controllers'
// own headers and classes are the original's.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <hardware_interface/hardware_interface_exception.h>
#include <hardware_interface/joint_command_interface.h>
#include <ros/console.h>
#include <ros/node_handle.h>

namespace forward_command_controller
{
namespace internal
{

/// The required `joint` parameter of controller namespace n; false (ERROR naming the namespace) when unset.
inline bool getJointName(const ros::NodeHandle& n, std::string& joint_name)
{
  if (n.getParam("joint", joint_name))
    return true;
  ROS_ERROR("No joint given (namespace: %s)", n.getNamespace().c_str());
  return false;
}

/// The required, non-empty `joints` list of controller namespace n; false with an ERROR otherwise.
inline bool getJointNames(const ros::NodeHandle& n, std::vector<std::string>& joint_names)
{
  const std::string param_name = "joints";
  if (!n.getParam(param_name, joint_names))
  {
    ROS_ERROR_STREAM("Failed to getParam '" << param_name << "' (namespace: " << n.getNamespace() << ").");
    return false;
  }
  if (joint_names.empty())
  {
    ROS_ERROR_STREAM("List of joint names is empty.");
    return false;
  }
  return true;
}

/// hw->getHandle(joint_name); false with an ERROR naming the joint, n's namespace and the reason
/// when the interface has no such joint.
template <class HardwareInterface>
bool getJointHandle(HardwareInterface* hw, const std::string& joint_name, const ros::NodeHandle& n,
                    hardware_interface::JointHandle& handle)
{
  try
  {
    handle = hw->getHandle(joint_name);
  }
  catch (const hardware_interface::HardwareInterfaceException& e)
  {
    ROS_ERROR("Could not get joint '%s' (namespace: %s): %s", joint_name.c_str(), n.getNamespace().c_str(), e.what());
    return false;
  }
  return true;
}

/// Appends the handle of joint `name` to `handles` (group controllers); false with the interface's
/// exception text when it has no such joint.
template <class HardwareInterface>
bool appendJointHandle(HardwareInterface* hw, const std::string& name,
                       std::vector<hardware_interface::JointHandle>& handles)
{
  try
  {
    handles.push_back(hw->getHandle(name));
  }
  catch (const hardware_interface::HardwareInterfaceException& e)
  {
    ROS_ERROR_STREAM("Exception thrown: " << e.what());
    return false;
  }
  return true;
}

/// The handle of every joint in `joint_names`, in order; false at the first missing joint.
template <class HardwareInterface>
bool getJointHandles(HardwareInterface* hw, const std::vector<std::string>& joint_names,
                     std::vector<hardware_interface::JointHandle>& handles)
{
  handles.clear();
  for (const std::string& name : joint_names)
  {
    if (!appendJointHandle(hw, name, handles))
      return false;
  }
  return true;
}

/// A group command (std_msgs/Float64MultiArray data) that can be executed: one finite value per
/// joint. Otherwise false and `error` says why (the caller logs it, throttled per controller).
inline bool checkGroupCommand(const std::vector<double>& data, unsigned int n_joints, std::string& error)
{
  std::ostringstream out;
  if (data.size() != n_joints)
  {
    out << "Dimension of command (" << data.size() << ") does not match number of joints (" << n_joints
        << ")! Not executing!";
    error = out.str();
    return false;
  }
  for (double value : data)
  {
    if (!std::isfinite(value))
    {
      out << "Command holds a non-finite value (" << value << ")! Not executing!";
      error = out.str();
      return false;
    }
  }
  return true;
}

}  // namespace internal
}  // namespace forward_command_controller
