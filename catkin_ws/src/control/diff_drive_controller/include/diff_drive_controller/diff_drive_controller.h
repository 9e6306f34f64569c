// Re-implementation of diff_drive_controller/diff_drive_controller.h (ros_controllers 0.21):
// a differential drive base on a VelocityJointInterface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <boost/thread/recursive_mutex.hpp>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <controller_interface/controller.h>
#include <diff_drive_controller/DiffDriveControllerConfig.h>
#include <diff_drive_controller/odometry.h>
#include <diff_drive_controller/speed_limiter.h>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/TwistStamped.h>
#include <hardware_interface/joint_command_interface.h>
#include <nav_msgs/Odometry.h>
#include <realtime_tools/realtime_buffer.h>
#include <realtime_tools/realtime_publisher.h>
#include <ros/node_handle.h>
#include <tf2_msgs/TFMessage.h>

namespace diff_drive_controller
{

/**
 * Takes geometry_msgs/Twist on `cmd_vel` (linear.x [m/s], angular.z [rad/s]), limits it, and
 * commands the wheel velocities [rad/s]; integrates odometry from the wheel positions and
 * publishes `odom` (nav_msgs/Odometry) and odom -> base on /tf. Parameters: see README.md
 * (those of ros_controllers 0.21, same defaults).
 */
class DiffDriveController : public controller_interface::Controller<hardware_interface::VelocityJointInterface>
{
public:
  DiffDriveController();

  bool init(hardware_interface::VelocityJointInterface* hw, ros::NodeHandle& root_nh,
            ros::NodeHandle& controller_nh) override;
  void update(const ros::Time& time, const ros::Duration& period) override;
  /// Brakes and resets the odometry's velocity estimates.
  void starting(const ros::Time& time) override;
  /// Brakes.
  void stopping(const ros::Time& time) override;

private:
  struct Commands
  {
    double lin = 0.0;  ///< [m/s]
    double ang = 0.0;  ///< [rad/s]
    ros::Time stamp = ros::Time(0.0);
  };

  /// Values that dynamic_reconfigure may change while running.
  struct DynamicParams
  {
    double left_wheel_radius_multiplier = 1.0;
    double right_wheel_radius_multiplier = 1.0;
    double wheel_separation_multiplier = 1.0;
    double publish_rate = 50.0;
    bool enable_odom_tf = true;
  };

  std::string name_;

  ros::Duration publish_period_;
  ros::Time last_state_publish_time_;
  bool open_loop_;

  std::vector<hardware_interface::JointHandle> left_wheel_joints_;
  std::vector<hardware_interface::JointHandle> right_wheel_joints_;

  ros::Time time_previous_;
  std::vector<double> vel_left_previous_;
  std::vector<double> vel_right_previous_;
  double vel_left_desired_previous_ = 0.0;
  double vel_right_desired_previous_ = 0.0;

  realtime_tools::RealtimeBuffer<Commands> command_;
  Commands command_struct_;
  ros::Subscriber sub_command_;

  std::shared_ptr<realtime_tools::RealtimePublisher<geometry_msgs::TwistStamped>> cmd_vel_pub_;
  std::shared_ptr<realtime_tools::RealtimePublisher<nav_msgs::Odometry>> odom_pub_;
  std::shared_ptr<realtime_tools::RealtimePublisher<tf2_msgs::TFMessage>> tf_odom_pub_;
  std::shared_ptr<realtime_tools::RealtimePublisher<control_msgs::JointTrajectoryControllerState>>
      controller_state_pub_;

  Odometry odometry_;

  double wheel_separation_;  ///< [m]
  double wheel_radius_;      ///< [m]
  double wheel_separation_multiplier_;
  double left_wheel_radius_multiplier_;
  double right_wheel_radius_multiplier_;

  double cmd_vel_timeout_;  ///< [s]
  bool allow_multiple_cmd_vel_publishers_;
  std::string base_frame_id_;
  std::string odom_frame_id_;
  bool enable_odom_tf_;
  std::size_t wheel_joints_size_;

  Commands last1_cmd_;  ///< command before the last one (jerk limit)
  Commands last0_cmd_;  ///< last command sent
  SpeedLimiter limiter_lin_;
  SpeedLimiter limiter_ang_;

  bool publish_cmd_;
  bool publish_wheel_joint_controller_state_;

  realtime_tools::RealtimeBuffer<DynamicParams> dynamic_params_;
  typedef dynamic_reconfigure::Server<DiffDriveControllerConfig> ReconfigureServer;
  std::shared_ptr<ReconfigureServer> dyn_reconf_server_;
  boost::recursive_mutex dyn_reconf_server_mutex_;

  void brake();
  void cmdVelCallback(const geometry_msgs::Twist& command);
  bool getWheelNames(ros::NodeHandle& controller_nh, const std::string& wheel_param,
                     std::vector<std::string>& wheel_names);
  bool setOdomParamsFromUrdf(ros::NodeHandle& root_nh, const std::string& left_wheel_name,
                             const std::string& right_wheel_name, bool lookup_wheel_separation,
                             bool lookup_wheel_radius);
  bool setOdomPubFields(ros::NodeHandle& root_nh, ros::NodeHandle& controller_nh);
  void reconfCallback(DiffDriveControllerConfig& config, uint32_t level);
  void updateDynamicParams();
  double readOdometryParams(ros::NodeHandle& controller_nh);
  void readCommandParams(ros::NodeHandle& controller_nh);
  void setupWheelStatePublisher(ros::NodeHandle& controller_nh, const std::vector<std::string>& left_wheel_names,
                                const std::vector<std::string>& right_wheel_names);
  void setupDynamicReconfigure(ros::NodeHandle& controller_nh, double publish_rate);
  void publishOdometry(const ros::Time& time);
  void publishWheelData(const ros::Time& time, const ros::Duration& period, const Commands& curr_cmd,
                        double wheel_separation, double left_wheel_radius, double right_wheel_radius);
};

}  // namespace diff_drive_controller
