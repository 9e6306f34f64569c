#include <diff_drive_controller/diff_drive_controller.h>

#include <cmath>
#include <limits>

#include <hardware_interface/hardware_interface_exception.h>
#include <pluginlib/class_list_macros.hpp>

namespace diff_drive_controller
{
namespace
{

geometry_msgs::Quaternion quaternionFromYaw(double yaw)
{
  geometry_msgs::Quaternion q;
  q.z = std::sin(yaw * 0.5);
  q.w = std::cos(yaw * 0.5);
  return q;
}

/// 1/rate as a Duration; a rate <= 0 publishes (practically) never.
ros::Duration periodOf(double rate)
{
  return rate > 0.0 ? ros::Duration(1.0 / rate) : ros::Duration(std::numeric_limits<int32_t>::max() / 2, 0);
}

}  // namespace

DiffDriveController::DiffDriveController()
  : open_loop_(false)
  , command_struct_()
  , wheel_separation_(0.0)
  , wheel_radius_(0.0)
  , wheel_separation_multiplier_(1.0)
  , left_wheel_radius_multiplier_(1.0)
  , right_wheel_radius_multiplier_(1.0)
  , cmd_vel_timeout_(0.5)
  , allow_multiple_cmd_vel_publishers_(true)
  , base_frame_id_("base_link")
  , odom_frame_id_("odom")
  , enable_odom_tf_(true)
  , wheel_joints_size_(0)
  , publish_cmd_(false)
  , publish_wheel_joint_controller_state_(false)
{
}

bool DiffDriveController::init(hardware_interface::VelocityJointInterface* hw, ros::NodeHandle& root_nh,
                               ros::NodeHandle& controller_nh)
{
  const std::string complete_ns = controller_nh.getNamespace();
  name_ = complete_ns.substr(complete_ns.find_last_of('/') + 1);

  std::vector<std::string> left_wheel_names, right_wheel_names;
  if (!getWheelNames(controller_nh, "left_wheel", left_wheel_names) ||
      !getWheelNames(controller_nh, "right_wheel", right_wheel_names))
    return false;
  if (left_wheel_names.size() != right_wheel_names.size())
  {
    ROS_ERROR_STREAM_NAMED(name_, "#left wheels (" << left_wheel_names.size() << ") != "
                                                   << "#right wheels (" << right_wheel_names.size() << ").");
    return false;
  }
  wheel_joints_size_ = left_wheel_names.size();
  left_wheel_joints_.resize(wheel_joints_size_);
  right_wheel_joints_.resize(wheel_joints_size_);

  const double publish_rate = readOdometryParams(controller_nh);
  publish_period_ = periodOf(publish_rate);
  readCommandParams(controller_nh);

  // wheel geometry: parameters, else the URDF
  const bool lookup_wheel_separation = !controller_nh.getParam("wheel_separation", wheel_separation_);
  const bool lookup_wheel_radius = !controller_nh.getParam("wheel_radius", wheel_radius_);
  if (!setOdomParamsFromUrdf(root_nh, left_wheel_names[0], right_wheel_names[0], lookup_wheel_separation,
                             lookup_wheel_radius))
    return false;
  if (!(wheel_separation_ > 0.0) || !(wheel_radius_ > 0.0))
  {
    ROS_ERROR_STREAM_NAMED(name_, "Wheel separation (" << wheel_separation_ << ") and wheel radius (" << wheel_radius_
                                                       << ") must be positive.");
    return false;
  }

  const double ws = wheel_separation_multiplier_ * wheel_separation_;
  const double lwr = left_wheel_radius_multiplier_ * wheel_radius_;
  const double rwr = right_wheel_radius_multiplier_ * wheel_radius_;
  odometry_.setWheelParams(ws, lwr, rwr);
  ROS_INFO_STREAM_NAMED(name_, "Odometry params : wheel separation " << ws << ", left wheel radius " << lwr
                                                                     << ", right wheel radius " << rwr);

  if (publish_cmd_)
    cmd_vel_pub_ = std::make_shared<realtime_tools::RealtimePublisher<geometry_msgs::TwistStamped>>(controller_nh,
                                                                                                    "cmd_vel_out", 100);

  if (publish_wheel_joint_controller_state_)
    setupWheelStatePublisher(controller_nh, left_wheel_names, right_wheel_names);

  if (!setOdomPubFields(root_nh, controller_nh))
    return false;

  for (std::size_t i = 0; i < wheel_joints_size_; ++i)
  {
    ROS_INFO_STREAM_NAMED(
        name_, "Adding left wheel with joint name: " << left_wheel_names[i]
                                                     << " and right wheel with joint name: " << right_wheel_names[i]);
    try
    {
      left_wheel_joints_[i] = hw->getHandle(left_wheel_names[i]);
      right_wheel_joints_[i] = hw->getHandle(right_wheel_names[i]);
    }
    catch (const hardware_interface::HardwareInterfaceException& e)
    {
      ROS_ERROR_STREAM_NAMED(name_, "Could not get the wheel joints: " << e.what());
      return false;
    }
  }

  sub_command_ = controller_nh.subscribe("cmd_vel", 1, &DiffDriveController::cmdVelCallback, this);

  setupDynamicReconfigure(controller_nh, publish_rate);
  return true;
}

void DiffDriveController::update(const ros::Time& time, const ros::Duration& period)
{
  updateDynamicParams();

  const double ws = wheel_separation_multiplier_ * wheel_separation_;
  const double lwr = left_wheel_radius_multiplier_ * wheel_radius_;
  const double rwr = right_wheel_radius_multiplier_ * wheel_radius_;
  odometry_.setWheelParams(ws, lwr, rwr);

  // odometry
  if (open_loop_)
  {
    odometry_.updateOpenLoop(last0_cmd_.lin, last0_cmd_.ang, time);
  }
  else
  {
    double left_pos = 0.0, right_pos = 0.0;
    for (std::size_t i = 0; i < wheel_joints_size_; ++i)
    {
      const double lp = left_wheel_joints_[i].getPosition();
      const double rp = right_wheel_joints_[i].getPosition();
      if (std::isnan(lp) || std::isnan(rp))
        return;  // no valid wheel state this cycle (e.g. hardware stopped): skip it
      left_pos += lp;
      right_pos += rp;
    }
    left_pos /= wheel_joints_size_;
    right_pos /= wheel_joints_size_;
    odometry_.update(left_pos, right_pos, time);
  }

  if (last_state_publish_time_ + publish_period_ < time)
    publishOdometry(time);

  // command
  Commands curr_cmd = *command_.readFromRT();
  const double dt = (time - curr_cmd.stamp).toSec();
  if (dt > cmd_vel_timeout_)
  {
    curr_cmd.lin = 0.0;
    curr_cmd.ang = 0.0;
  }

  const double cmd_dt = period.toSec();
  limiter_lin_.limit(curr_cmd.lin, last0_cmd_.lin, last1_cmd_.lin, cmd_dt);
  limiter_ang_.limit(curr_cmd.ang, last0_cmd_.ang, last1_cmd_.ang, cmd_dt);
  last1_cmd_ = last0_cmd_;
  last0_cmd_ = curr_cmd;

  if (publish_cmd_ && cmd_vel_pub_ && cmd_vel_pub_->trylock())
  {
    cmd_vel_pub_->msg_.header.stamp = time;
    cmd_vel_pub_->msg_.twist.linear.x = curr_cmd.lin;
    cmd_vel_pub_->msg_.twist.angular.z = curr_cmd.ang;
    cmd_vel_pub_->unlockAndPublish();
  }

  const double vel_left = (curr_cmd.lin - curr_cmd.ang * ws / 2.0) / lwr;
  const double vel_right = (curr_cmd.lin + curr_cmd.ang * ws / 2.0) / rwr;
  for (std::size_t i = 0; i < wheel_joints_size_; ++i)
  {
    left_wheel_joints_[i].setCommand(vel_left);
    right_wheel_joints_[i].setCommand(vel_right);
  }

  publishWheelData(time, period, curr_cmd, ws, lwr, rwr);
  time_previous_ = time;
}

/// Odometry and its odom -> base transform, when the publishers are free.
void DiffDriveController::publishOdometry(const ros::Time& time)
{
  last_state_publish_time_ += publish_period_;
  const geometry_msgs::Quaternion orientation = quaternionFromYaw(odometry_.getHeading());

  if (odom_pub_->trylock())
  {
    nav_msgs::Odometry& msg = odom_pub_->msg_;
    msg.header.stamp = time;
    msg.pose.pose.position.x = odometry_.getX();
    msg.pose.pose.position.y = odometry_.getY();
    msg.pose.pose.orientation = orientation;
    msg.twist.twist.linear.x = odometry_.getLinear();
    msg.twist.twist.angular.z = odometry_.getAngular();
    odom_pub_->unlockAndPublish();
  }
  if (enable_odom_tf_ && tf_odom_pub_->trylock())
  {
    geometry_msgs::TransformStamped& odom_frame = tf_odom_pub_->msg_.transforms[0];
    odom_frame.header.stamp = time;
    odom_frame.transform.translation.x = odometry_.getX();
    odom_frame.transform.translation.y = odometry_.getY();
    odom_frame.transform.rotation = orientation;
    tf_odom_pub_->unlockAndPublish();
  }
}

/// The wheel_joint_controller_state publisher and its message's fixed fields.
void DiffDriveController::setupWheelStatePublisher(ros::NodeHandle& controller_nh,
                                                   const std::vector<std::string>& left_wheel_names,
                                                   const std::vector<std::string>& right_wheel_names)
{
  controller_state_pub_ =
      std::make_shared<realtime_tools::RealtimePublisher<control_msgs::JointTrajectoryControllerState>>(
          controller_nh, "wheel_joint_controller_state", 100);
  control_msgs::JointTrajectoryControllerState& msg = controller_state_pub_->msg_;
  const std::size_t num_wheels = wheel_joints_size_ * 2;
  msg.joint_names.resize(num_wheels);
  for (trajectory_msgs::JointTrajectoryPoint* point : { &msg.desired, &msg.actual, &msg.error })
  {
    point->positions.assign(num_wheels, 0.0);
    point->velocities.assign(num_wheels, 0.0);
    point->accelerations.assign(num_wheels, 0.0);
    point->effort.assign(num_wheels, 0.0);
  }
  for (std::size_t i = 0; i < wheel_joints_size_; ++i)
  {
    msg.joint_names[i] = left_wheel_names[i];
    msg.joint_names[i + wheel_joints_size_] = right_wheel_names[i];
  }
  vel_left_previous_.assign(wheel_joints_size_, 0.0);
  vel_right_previous_.assign(wheel_joints_size_, 0.0);
}

void DiffDriveController::setupDynamicReconfigure(ros::NodeHandle& controller_nh, double publish_rate)
{
  DynamicParams dynamic_params;
  dynamic_params.left_wheel_radius_multiplier = left_wheel_radius_multiplier_;
  dynamic_params.right_wheel_radius_multiplier = right_wheel_radius_multiplier_;
  dynamic_params.wheel_separation_multiplier = wheel_separation_multiplier_;
  dynamic_params.publish_rate = publish_rate;
  dynamic_params.enable_odom_tf = enable_odom_tf_;
  dynamic_params_.initRT(dynamic_params);

  DiffDriveControllerConfig config;
  config.left_wheel_radius_multiplier = left_wheel_radius_multiplier_;
  config.right_wheel_radius_multiplier = right_wheel_radius_multiplier_;
  config.wheel_separation_multiplier = wheel_separation_multiplier_;
  config.publish_rate = publish_rate;
  config.enable_odom_tf = enable_odom_tf_;
  dyn_reconf_server_ = std::make_shared<ReconfigureServer>(dyn_reconf_server_mutex_, controller_nh);
  {
    boost::recursive_mutex::scoped_lock lock(dyn_reconf_server_mutex_);
    dyn_reconf_server_->updateConfig(config);
  }
  dyn_reconf_server_->setCallback([this](DiffDriveControllerConfig& c, uint32_t level) { reconfCallback(c, level); });
}

void DiffDriveController::starting(const ros::Time& time)
{
  brake();
  last_state_publish_time_ = time;
  time_previous_ = time;
  odometry_.init(time);
}

void DiffDriveController::stopping(const ros::Time& /*time*/) { brake(); }

void DiffDriveController::brake()
{
  for (std::size_t i = 0; i < wheel_joints_size_; ++i)
  {
    left_wheel_joints_[i].setCommand(0.0);
    right_wheel_joints_[i].setCommand(0.0);
  }
}

void DiffDriveController::cmdVelCallback(const geometry_msgs::Twist& command)
{
  if (!isRunning())
  {
    ROS_ERROR_THROTTLE_NAMED(1.0, name_, "Can't accept new commands. Controller is not running.");
    return;
  }
  if (!allow_multiple_cmd_vel_publishers_ && sub_command_.getNumPublishers() > 1)
  {
    ROS_ERROR_STREAM_THROTTLE_NAMED(
        1.0, name_,
        "Detected " << sub_command_.getNumPublishers() << " publishers. Only 1 publisher is allowed. Going to brake.");
    // brake through the realtime loop (a zero command) rather than touching the joints from here
    command_struct_.lin = 0.0;
    command_struct_.ang = 0.0;
    command_struct_.stamp = ros::Time::now();
    command_.writeFromNonRT(command_struct_);
    return;
  }
  if (!std::isfinite(command.angular.z) || !std::isfinite(command.linear.x))
  {
    ROS_WARN_THROTTLE(1.0, "Received NaN in velocity command. Ignoring.");
    return;
  }
  command_struct_.ang = command.angular.z;
  command_struct_.lin = command.linear.x;
  command_struct_.stamp = ros::Time::now();
  command_.writeFromNonRT(command_struct_);
  ROS_DEBUG_STREAM_NAMED(name_, "Added values to command. "
                                    << "Ang: " << command_struct_.ang << ", "
                                    << "Lin: " << command_struct_.lin << ", "
                                    << "Stamp: " << command_struct_.stamp);
}

void DiffDriveController::reconfCallback(DiffDriveControllerConfig& config, uint32_t /*level*/)
{
  DynamicParams dynamic_params;
  dynamic_params.left_wheel_radius_multiplier = config.left_wheel_radius_multiplier;
  dynamic_params.right_wheel_radius_multiplier = config.right_wheel_radius_multiplier;
  dynamic_params.wheel_separation_multiplier = config.wheel_separation_multiplier;
  dynamic_params.publish_rate = config.publish_rate;
  dynamic_params.enable_odom_tf = config.enable_odom_tf;
  dynamic_params_.writeFromNonRT(dynamic_params);
  ROS_INFO_STREAM_NAMED(name_,
                        "Dynamic Reconfigure:\n"
                            << "Left wheel radius multiplier: " << dynamic_params.left_wheel_radius_multiplier
                            << "\nRight wheel radius multiplier: " << dynamic_params.right_wheel_radius_multiplier
                            << "\nWheel separation multiplier: " << dynamic_params.wheel_separation_multiplier
                            << "\nPublish rate: " << dynamic_params.publish_rate
                            << "\nEnable odom tf: " << dynamic_params.enable_odom_tf);
}

void DiffDriveController::updateDynamicParams()
{
  const DynamicParams dynamic_params = *dynamic_params_.readFromRT();
  left_wheel_radius_multiplier_ = dynamic_params.left_wheel_radius_multiplier;
  right_wheel_radius_multiplier_ = dynamic_params.right_wheel_radius_multiplier;
  wheel_separation_multiplier_ = dynamic_params.wheel_separation_multiplier;
  publish_period_ = periodOf(dynamic_params.publish_rate);
  enable_odom_tf_ = dynamic_params.enable_odom_tf;
}

void DiffDriveController::publishWheelData(const ros::Time& time, const ros::Duration& period, const Commands& curr_cmd,
                                           double wheel_separation, double left_wheel_radius, double right_wheel_radius)
{
  if (!publish_wheel_joint_controller_state_ || !controller_state_pub_ || !controller_state_pub_->trylock())
    return;

  const double cmd_dt = period.toSec();
  const double vel_left_desired = (curr_cmd.lin - curr_cmd.ang * wheel_separation / 2.0) / left_wheel_radius;
  const double vel_right_desired = (curr_cmd.lin + curr_cmd.ang * wheel_separation / 2.0) / right_wheel_radius;
  const double control_duration = (time - time_previous_).toSec();
  const std::size_t n = wheel_joints_size_;

  control_msgs::JointTrajectoryControllerState& msg = controller_state_pub_->msg_;
  msg.header.stamp = time;
  for (std::size_t i = 0; i < n; ++i)
  {
    const hardware_interface::JointHandle* joints[2] = { &left_wheel_joints_[i], &right_wheel_joints_[i] };
    std::vector<double>* previous[2] = { &vel_left_previous_, &vel_right_previous_ };
    const double desired[2] = { vel_left_desired, vel_right_desired };
    const double desired_previous[2] = { vel_left_desired_previous_, vel_right_desired_previous_ };
    for (int side = 0; side < 2; ++side)
    {
      const std::size_t k = i + side * n;
      const double vel = joints[side]->getVelocity();
      msg.actual.positions[k] = joints[side]->getPosition();
      msg.actual.velocities[k] = vel;
      msg.actual.accelerations[k] = control_duration > 0.0 ? (vel - (*previous[side])[i]) / control_duration : 0.0;
      msg.actual.effort[k] = joints[side]->getEffort();

      msg.desired.positions[k] += desired[side] * cmd_dt;
      msg.desired.velocities[k] = desired[side];
      msg.desired.accelerations[k] = (desired[side] - desired_previous[side]) * cmd_dt;
      msg.desired.effort[k] = std::numeric_limits<double>::quiet_NaN();

      msg.error.positions[k] = msg.desired.positions[k] - msg.actual.positions[k];
      msg.error.velocities[k] = msg.desired.velocities[k] - msg.actual.velocities[k];
      msg.error.accelerations[k] = msg.desired.accelerations[k] - msg.actual.accelerations[k];
      msg.error.effort[k] = msg.desired.effort[k] - msg.actual.effort[k];

      (*previous[side])[i] = vel;
    }
  }
  vel_left_desired_previous_ = vel_left_desired;
  vel_right_desired_previous_ = vel_right_desired;
  controller_state_pub_->unlockAndPublish();
}

}  // namespace diff_drive_controller

PLUGINLIB_EXPORT_CLASS(diff_drive_controller::DiffDriveController, controller_interface::ControllerBase)
