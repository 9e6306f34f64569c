// DiffRobotHW: a RobotHW of its own for the course robot in the simulator. Two wheel joints
// with an EffortJointInterface; read() takes the newest state the simulator published on
// NS/ode_sim/joint_states, write() sends the effort commands on NS/ode_sim/joint_commands
// stamped with the state's time (the bridge contract of ode_sim, doc/ros_control_bridge.md).
// The robot's URDF must say <controllerNode>false</controllerNode> so that the simulator
// starts no controller manager of its own.
#ifndef MY_ROBOT_SIMULATION_CONTROL_DIFFROBOT_HW_H
#define MY_ROBOT_SIMULATION_CONTROL_DIFFROBOT_HW_H

#include <mutex>
#include <string>
#include <vector>

#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

namespace my_robot_simulation_control
{

class DiffRobotHW : public hardware_interface::RobotHW
{
public:
  /// root_nh: the robot namespace (/diffrobot); robot_hw_nh: ~ (param `joints`, list of names)
  bool init(ros::NodeHandle& root_nh, ros::NodeHandle& robot_hw_nh) override;

  /// Waits (wall clock) for the next joint state from the simulator. False on timeout.
  bool waitForState(const ros::WallDuration& timeout);

  /// Sim time of the newest state (t_k).
  ros::Time stateTime() const { return state_time_; }

  void read(const ros::Time& time, const ros::Duration& period) override;
  void write(const ros::Time& time, const ros::Duration& period) override;

private:
  void stateCallback(const sensor_msgs::JointStateConstPtr& msg);

  std::vector<std::string> joint_names_;
  std::vector<double> pos_, vel_, eff_, cmd_;
  hardware_interface::JointStateInterface jnt_state_interface_;
  hardware_interface::EffortJointInterface jnt_eff_interface_;

  ros::CallbackQueue queue_;
  ros::Subscriber state_sub_;
  ros::Publisher command_pub_;
  sensor_msgs::JointStateConstPtr state_;
  bool fresh_ = false;
  ros::Time state_time_;
};

}  // namespace my_robot_simulation_control

#endif  // MY_ROBOT_SIMULATION_CONTROL_DIFFROBOT_HW_H
