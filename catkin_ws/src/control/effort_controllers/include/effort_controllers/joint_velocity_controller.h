// Re-implementation of effort_controllers/joint_velocity_controller.h (ros_controllers 0.21):
// PID from a velocity set point to a joint effort.
#pragma once

#include <memory>
#include <string>

#include <control_msgs/JointControllerState.h>
#include <control_toolbox/pid.h>
#include <controller_interface/controller.h>
#include <hardware_interface/joint_command_interface.h>
#include <realtime_tools/realtime_buffer.h>
#include <realtime_tools/realtime_publisher.h>
#include <ros/node_handle.h>
#include <std_msgs/Float64.h>

namespace effort_controllers
{

/**
 * Parameters: `joint` (required), `pid/...` (p required). Subscribes `command`
 * (std_msgs/Float64, [rad/s or m/s]); publishes `state` every 10th update. The set point is 0
 * when the controller starts.
 */
class JointVelocityController : public controller_interface::Controller<hardware_interface::EffortJointInterface>
{
public:
  JointVelocityController();
  ~JointVelocityController() override;

  bool init(hardware_interface::EffortJointInterface* robot, const std::string& joint_name,
            const control_toolbox::Pid& pid);
  bool init(hardware_interface::EffortJointInterface* robot, ros::NodeHandle& n) override;

  /// Velocity set point [rad/s or m/s] (non-realtime).
  void setCommand(double cmd);
  void getCommand(double& cmd);

  void starting(const ros::Time& time) override;
  void update(const ros::Time& time, const ros::Duration& period) override;

  void getGains(double& p, double& i, double& d, double& i_max, double& i_min);
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup);
  void setGains(const double& p, const double& i, const double& d, const double& i_max, const double& i_min,
                const bool& antiwindup = false);
  void printDebug();
  std::string getJointName();

  hardware_interface::JointHandle joint_;
  double command_ = 0.0;

private:
  int loop_count_ = 0;
  control_toolbox::Pid pid_controller_;
  realtime_tools::RealtimeBuffer<double> command_buffer_;
  std::unique_ptr<realtime_tools::RealtimePublisher<control_msgs::JointControllerState>> controller_state_publisher_;
  ros::Subscriber sub_command_;
  std::string namespace_;

  void setCommandCB(const std_msgs::Float64ConstPtr& msg);
};

}  // namespace effort_controllers
