// gazebo_ros_control::RobotHWSim: the plugin interface of a simulated robot's hardware, as
// upstream (gazebo_ros_control/robot_hw_sim.h), adapted to ode_sim: the "model" is the
// bridge (BridgeModel: the simulator's joint states in, joint commands out) instead of a
// gazebo::physics::Model, and the transmissions arrive already resolved to one joint each
// (the simulator parses them and lists the joints in NS/ode_sim/joints).
#ifndef GAZEBO_ROS_CONTROL_ROBOT_HW_SIM_H
#define GAZEBO_ROS_CONTROL_ROBOT_HW_SIM_H

#include <string>

#include <hardware_interface/robot_hw.h>
#include <ros/ros.h>

#include <gazebo_ros_control/bridge_model.h>

namespace gazebo_ros_control
{

class RobotHWSim : public hardware_interface::RobotHW
{
public:
  virtual ~RobotHWSim() {}

  /// Registers the hardware interfaces of the model's joints.
  /// @param robot_namespace the plugin's namespace (NS)
  /// @param model_nh a NodeHandle in NS
  /// @param parent_model the bridge; must outlive this object
  virtual bool initSim(const std::string& robot_namespace, ros::NodeHandle model_nh, BridgeModel* parent_model) = 0;

  /// Copies the state of time `time` from the model into the joint handles' data.
  virtual void readSim(ros::Time time, ros::Duration period) = 0;

  /// Enforces limits and hands the commands to the model.
  virtual void writeSim(ros::Time time, ros::Duration period) = 0;

  /// While active: efforts 0, velocities 0, positions held where the stop began.
  virtual void eStopActive(const bool active) { (void)active; }
};

}  // namespace gazebo_ros_control

#endif  // GAZEBO_ROS_CONTROL_ROBOT_HW_SIM_H
