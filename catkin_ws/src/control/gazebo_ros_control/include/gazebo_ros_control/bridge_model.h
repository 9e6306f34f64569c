// What DefaultRobotHWSim sees of the simulated robot: the bridge's joints, the latest joint
// state received from the simulator and the commands to send back. Plain data, no ROS: the
// node fills the state from NS/ode_sim/joint_states and publishes the commands.
#ifndef GAZEBO_ROS_CONTROL_BRIDGE_MODEL_H
#define GAZEBO_ROS_CONTROL_BRIDGE_MODEL_H

#include <cstddef>
#include <string>
#include <vector>

#include <gazebo_ros_control/bridge_joint.h>

namespace gazebo_ros_control
{

class BridgeModel
{
public:
  explicit BridgeModel(std::vector<BridgeJoint> joints);

  const std::vector<BridgeJoint>& joints() const { return joints_; }
  std::size_t size() const { return joints_.size(); }

  /// Takes a state message's arrays (joints matched by name, any order; empty velocity or
  /// effort arrays read as 0). Returns false and says why in *error when a bridge joint
  /// is missing or an array is too short; the previous state is then kept.
  bool setState(const std::vector<std::string>& names, const std::vector<double>& position,
                const std::vector<double>& velocity, const std::vector<double>& effort, std::string* error);

  /// Takes the state of every joint in joints() order (arrays of size()).
  void setState(const double* position, const double* velocity, const double* effort);

  double position(std::size_t j) const { return position_[j]; }
  double velocity(std::size_t j) const { return velocity_[j]; }
  double effort(std::size_t j) const { return effort_[j]; }

  /// The command of joint j in its interface's unit; NaN = none yet (the simulator keeps
  /// its own default: hold still).
  void setCommand(std::size_t j, double value) { command_[j] = value; }
  double command(std::size_t j) const { return command_[j]; }

private:
  std::vector<BridgeJoint> joints_;
  std::vector<double> position_, velocity_, effort_, command_;
  std::vector<std::string> last_names_;  ///< names of the last state, for the fast path
  std::vector<std::size_t> index_;       ///< bridge joint j -> index in the message
};

}  // namespace gazebo_ros_control

#endif  // GAZEBO_ROS_CONTROL_BRIDGE_MODEL_H
