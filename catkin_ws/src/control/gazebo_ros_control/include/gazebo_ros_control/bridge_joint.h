// One joint of the ros_control bridge as the simulator describes it in NS/ode_sim/joints
// (see ode_sim/doc/ros_control_bridge.md): name, interface, reduction and the URDF limits.
#ifndef GAZEBO_ROS_CONTROL_BRIDGE_JOINT_H
#define GAZEBO_ROS_CONTROL_BRIDGE_JOINT_H

#include <string>

namespace gazebo_ros_control
{

/// The hardware interface a transmission gives its joint. STATE joints are read-only.
enum class JointInterface
{
  STATE,
  EFFORT,
  VELOCITY,
  POSITION
};

struct BridgeJoint
{
  std::string name;
  JointInterface interface = JointInterface::STATE;
  double reduction = 1.0;  ///< the first actuator's mechanicalReduction
  bool has_position_limits = false;
  double lower = 0.0;  ///< [rad] or [m]
  double upper = 0.0;  ///< [rad] or [m]
  bool has_effort_limit = false;
  double effort = 0.0;  ///< [N·m] or [N], > 0
  bool has_velocity_limit = false;
  double velocity = 0.0;  ///< [rad/s] or [m/s], > 0
};

/// Parses "EffortJointInterface" or "hardware_interface/EffortJointInterface" (etc.).
/// Returns false for any other name.
bool parseJointInterface(const std::string& name, JointInterface* out);

/// The bare name ("EffortJointInterface", ...).
const char* jointInterfaceName(JointInterface interface);

}  // namespace gazebo_ros_control

#endif  // GAZEBO_ROS_CONTROL_BRIDGE_JOINT_H
