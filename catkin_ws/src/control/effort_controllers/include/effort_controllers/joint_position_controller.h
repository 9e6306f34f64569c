// Re-implementation of effort_controllers/joint_position_controller.h (ros_controllers 0.21):
// PID from a position set point to a joint effort.
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
#include <urdf/model.h>

namespace effort_controllers
{

/**
 * Parameters (controller namespace): `joint` (required), `pid/{p,i,d,i_clamp,...}` (p required),
 * and `robot_description` found upward from the namespace (joint type and limits).
 * Subscribes `command` (std_msgs/Float64, position [rad or m]); publishes `state`
 * (control_msgs/JointControllerState) every 10th update.
 * Error: shortest angle within the limits for revolute joints, shortest angle for continuous
 * joints, difference for prismatic; set points are clamped to the URDF limits.
 */
class JointPositionController : public controller_interface::Controller<hardware_interface::EffortJointInterface>
{
public:
  /// Set point; the velocity set point is used (as the PID's error derivative) when has_velocity_.
  struct Commands
  {
    double position_ = 0.0;
    double velocity_ = 0.0;
    bool has_velocity_ = false;
  };

  JointPositionController();
  ~JointPositionController() override;

  bool init(hardware_interface::EffortJointInterface* robot, const std::string& joint_name,
            const control_toolbox::Pid& pid);
  bool init(hardware_interface::EffortJointInterface* robot, ros::NodeHandle& n) override;

  /// Position set point [rad or m] (non-realtime).
  void setCommand(double pos_target);
  /// Position [rad or m] and velocity [rad/s or m/s] set points (non-realtime).
  void setCommand(double pos_target, double vel_target);

  void starting(const ros::Time& time) override;
  void update(const ros::Time& time, const ros::Duration& period) override;

  void getGains(double& p, double& i, double& d, double& i_max, double& i_min);
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup);
  void setGains(const double& p, const double& i, const double& d, const double& i_max, const double& i_min,
                const bool& antiwindup = false);
  void printDebug();
  std::string getJointName();
  double getPosition();

  hardware_interface::JointHandle joint_;
  urdf::JointConstSharedPtr joint_urdf_;
  realtime_tools::RealtimeBuffer<Commands> command_;
  Commands command_struct_;

private:
  int loop_count_ = 0;
  control_toolbox::Pid pid_controller_;
  std::unique_ptr<realtime_tools::RealtimePublisher<control_msgs::JointControllerState>> controller_state_publisher_;
  ros::Subscriber sub_command_;
  std::string namespace_;

  void setCommandCB(const std_msgs::Float64ConstPtr& msg);
  void enforceJointLimits(double& command);
};

}  // namespace effort_controllers
