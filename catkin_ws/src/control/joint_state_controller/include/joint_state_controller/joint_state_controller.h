// Re-implementation of joint_state_controller/joint_state_controller.h (ros_controllers 0.21):
// publishes the JointStateInterface's joints as sensor_msgs/JointState.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <controller_interface/controller.h>
#include <hardware_interface/joint_state_interface.h>
#include <realtime_tools/realtime_publisher.h>
#include <ros/node_handle.h>
#include <sensor_msgs/JointState.h>

namespace joint_state_controller
{

/**
 * Parameters (controller namespace): `publish_rate` [Hz] (required: ERROR
 * "Parameter 'publish_rate' not set"), `joints` (optional: subset and order; default all joints
 * of the interface), `extra_joints` (optional list of {name, position, velocity, effort} published
 * with constant values). Publishes `joint_states` in the controller manager's namespace
 * (root_nh), queue 4.
 */
class JointStateController : public controller_interface::Controller<hardware_interface::JointStateInterface>
{
public:
  JointStateController() = default;

  bool init(hardware_interface::JointStateInterface* hw, ros::NodeHandle& root_nh,
            ros::NodeHandle& controller_nh) override;
  void starting(const ros::Time& time) override;
  void update(const ros::Time& time, const ros::Duration& period) override;
  void stopping(const ros::Time& time) override;

private:
  std::vector<hardware_interface::JointStateHandle> joint_state_;
  std::shared_ptr<realtime_tools::RealtimePublisher<sensor_msgs::JointState>> realtime_pub_;
  ros::Time last_publish_time_;
  double publish_rate_ = 0.0;
  unsigned int num_hw_joints_ = 0;  ///< joints from the interface (extra joints come after them)

  void addExtraJoints(const ros::NodeHandle& nh, sensor_msgs::JointState& msg);
};

}  // namespace joint_state_controller
