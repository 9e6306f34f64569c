// Re-implementation of effort_controllers/joint_group_position_controller.h (ros_controllers
// 0.21): one PID per joint from position set points to efforts.
#pragma once

#include <string>
#include <vector>

#include <control_toolbox/pid.h>
#include <controller_interface/controller.h>
#include <hardware_interface/joint_command_interface.h>
#include <realtime_tools/realtime_buffer.h>
#include <ros/node_handle.h>
#include <std_msgs/Float64MultiArray.h>
#include <urdf/model.h>

namespace effort_controllers
{

/**
 * Parameters: `joints` (required, non-empty), `gains/<joint>/{p,i,d,...}` per joint (p
 * required), `robot_description` (searched upward). Subscribes `command`
 * (std_msgs/Float64MultiArray, one position per joint in `joints` order; another size is refused).
 * Starts holding the current positions.
 */
class JointGroupPositionController : public controller_interface::Controller<hardware_interface::EffortJointInterface>
{
public:
  JointGroupPositionController();
  ~JointGroupPositionController() override;

  bool init(hardware_interface::EffortJointInterface* robot, ros::NodeHandle& n) override;
  void starting(const ros::Time& time) override;
  void update(const ros::Time& time, const ros::Duration& period) override;

  std::vector<std::string> joint_names_;
  std::vector<hardware_interface::JointHandle> joints_;
  realtime_tools::RealtimeBuffer<std::vector<double>> commands_buffer_;
  unsigned int n_joints_ = 0;

private:
  ros::Subscriber sub_command_;
  std::vector<control_toolbox::Pid> pid_controllers_;
  std::vector<urdf::JointConstSharedPtr> joint_urdfs_;

  void commandCB(const std_msgs::Float64MultiArrayConstPtr& msg);
  void enforceJointLimits(double& command, unsigned int index);
};

}  // namespace effort_controllers
