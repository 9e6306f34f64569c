// gazebo_ros_control::DefaultRobotHWSim: one joint per transmission; a JointStateInterface
// with every joint and an Effort/Velocity/PositionJointInterface per the joint's
// <hardwareInterface>; URDF limits enforced on the commands (saturation as
// joint_limits_interface); e-stop. The PID of velocity/position joints with
// NS/gazebo_ros_control/pid_gains/JOINT runs in the simulator, every physics step.
#ifndef GAZEBO_ROS_CONTROL_DEFAULT_ROBOT_HW_SIM_H
#define GAZEBO_ROS_CONTROL_DEFAULT_ROBOT_HW_SIM_H

#include <string>
#include <vector>

#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>

#include <gazebo_ros_control/joint_saturation.h>
#include <gazebo_ros_control/robot_hw_sim.h>

namespace gazebo_ros_control
{

class DefaultRobotHWSim : public RobotHWSim
{
public:
  bool initSim(const std::string& robot_namespace, ros::NodeHandle model_nh, BridgeModel* parent_model) override;
  void readSim(ros::Time time, ros::Duration period) override;
  void writeSim(ros::Time time, ros::Duration period) override;
  void eStopActive(const bool active) override;

protected:
  double enforceAndStore(std::size_t j, double cmd, double dt);

  BridgeModel* model_ = nullptr;
  std::size_t n_dof_ = 0;
  std::vector<std::string> joint_names_;
  std::vector<JointInterface> joint_control_methods_;
  std::vector<double> joint_position_, joint_velocity_, joint_effort_;
  std::vector<double> joint_effort_command_, joint_velocity_command_, joint_position_command_;
  std::vector<double> last_joint_position_command_;
  std::vector<JointSaturation> saturation_;

  hardware_interface::JointStateInterface js_interface_;
  hardware_interface::EffortJointInterface ej_interface_;
  hardware_interface::VelocityJointInterface vj_interface_;
  hardware_interface::PositionJointInterface pj_interface_;

  bool e_stop_active_ = false;
  bool last_e_stop_active_ = false;
};

}  // namespace gazebo_ros_control

#endif  // GAZEBO_ROS_CONTROL_DEFAULT_ROBOT_HW_SIM_H
