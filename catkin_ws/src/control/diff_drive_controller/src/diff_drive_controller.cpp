#include <diff_drive_controller/diff_drive_controller.h>

#include <cmath>
#include <limits>

#include <hardware_interface/hardware_interface_exception.h>
#include <pluginlib/class_list_macros.hpp>
#include <urdf_parser/urdf_parser.h>

namespace diff_drive_controller
{
namespace
{

double euclideanOfVectors(const urdf::Vector3& a, const urdf::Vector3& b)
{
  return std::sqrt(std::pow(a.x - b.x, 2) + std::pow(a.y - b.y, 2) + std::pow(a.z - b.z, 2));
}

/// Collision geometry of `link` if it is of `type`, else null (with the original's messages).
const urdf::Geometry* collisionGeometry(const urdf::LinkConstSharedPtr& link, int type)
{
  if (!link)
  {
    ROS_ERROR("Link pointer is null.");
    return nullptr;
  }
  if (!link->collision)
  {
    ROS_ERROR_STREAM("Link " << link->name
                             << " does not have collision description. Add collision description for link to urdf.");
    return nullptr;
  }
  if (!link->collision->geometry)
  {
    ROS_ERROR_STREAM("Link " << link->name
                             << " does not have collision geometry description. Add collision geometry description "
                                "for link to urdf.");
    return nullptr;
  }
  if (link->collision->geometry->type != type)
    return nullptr;
  return link->collision->geometry.get();
}

/// Radius [m] of a wheel modelled as a cylinder or a sphere.
bool getWheelRadius(const urdf::LinkConstSharedPtr& wheel_link, double& wheel_radius)
{
  if (const urdf::Geometry* g = collisionGeometry(wheel_link, urdf::Geometry::CYLINDER))
  {
    wheel_radius = static_cast<const urdf::Cylinder*>(g)->radius;
    return true;
  }
  if (wheel_link && wheel_link->collision && wheel_link->collision->geometry)
  {
    if (const urdf::Geometry* g = collisionGeometry(wheel_link, urdf::Geometry::SPHERE))
    {
      wheel_radius = static_cast<const urdf::Sphere*>(g)->radius;
      return true;
    }
    ROS_ERROR_STREAM("Wheel link " << wheel_link->name << " is NOT modeled as a cylinder or sphere!");
  }
  return false;
}

/// Covariance diagonal: 6 numbers.
bool getCovarianceDiagonal(ros::NodeHandle& nh, const std::string& name, const std::string& controller,
                           double diagonal[6])
{
  XmlRpc::XmlRpcValue list;
  if (!nh.getParam(name, list) || list.getType() != XmlRpc::XmlRpcValue::TypeArray || list.size() != 6)
  {
    ROS_ERROR_STREAM_NAMED(controller, "Parameter '" << nh.resolveName(name)
                                                     << "' must be a list of 6 numbers (the covariance diagonal).");
    return false;
  }
  for (int i = 0; i < 6; ++i)
  {
    if (list[i].getType() == XmlRpc::XmlRpcValue::TypeDouble)
      diagonal[i] = static_cast<double>(list[i]);
    else if (list[i].getType() == XmlRpc::XmlRpcValue::TypeInt)
      diagonal[i] = static_cast<int>(list[i]);
    else
    {
      ROS_ERROR_STREAM_NAMED(controller, "Parameter '" << nh.resolveName(name) << "' #" << i << " isn't a number.");
      return false;
    }
  }
  return true;
}

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

  // odometry
  double publish_rate = 50.0;
  controller_nh.param("publish_rate", publish_rate, publish_rate);
  ROS_INFO_STREAM_NAMED(name_, "Controller state will be published at " << publish_rate << "Hz.");
  publish_period_ = periodOf(publish_rate);

  controller_nh.param("open_loop", open_loop_, open_loop_);

  controller_nh.param("wheel_separation_multiplier", wheel_separation_multiplier_, wheel_separation_multiplier_);
  ROS_INFO_STREAM_NAMED(name_, "Wheel separation will be multiplied by " << wheel_separation_multiplier_ << ".");
  if (controller_nh.hasParam("wheel_radius_multiplier"))
  {
    double wheel_radius_multiplier = 1.0;
    controller_nh.getParam("wheel_radius_multiplier", wheel_radius_multiplier);
    left_wheel_radius_multiplier_ = wheel_radius_multiplier;
    right_wheel_radius_multiplier_ = wheel_radius_multiplier;
  }
  else
  {
    controller_nh.param("left_wheel_radius_multiplier", left_wheel_radius_multiplier_, left_wheel_radius_multiplier_);
    controller_nh.param("right_wheel_radius_multiplier", right_wheel_radius_multiplier_,
                        right_wheel_radius_multiplier_);
  }
  ROS_INFO_STREAM_NAMED(name_, "Left wheel radius will be multiplied by " << left_wheel_radius_multiplier_ << ".");
  ROS_INFO_STREAM_NAMED(name_, "Right wheel radius will be multiplied by " << right_wheel_radius_multiplier_ << ".");

  int velocity_rolling_window_size = 10;
  controller_nh.param("velocity_rolling_window_size", velocity_rolling_window_size, velocity_rolling_window_size);
  ROS_INFO_STREAM_NAMED(name_, "Velocity rolling window size of " << velocity_rolling_window_size << ".");
  odometry_.setVelocityRollingWindowSize(velocity_rolling_window_size > 0 ? velocity_rolling_window_size : 1);

  // twist command
  controller_nh.param("cmd_vel_timeout", cmd_vel_timeout_, cmd_vel_timeout_);
  ROS_INFO_STREAM_NAMED(name_, "Velocity commands will be considered old if they are older than "
                                   << cmd_vel_timeout_ << "s.");
  controller_nh.param("allow_multiple_cmd_vel_publishers", allow_multiple_cmd_vel_publishers_,
                      allow_multiple_cmd_vel_publishers_);
  ROS_INFO_STREAM_NAMED(name_, "Allow mutiple cmd_vel publishers is "
                                   << (allow_multiple_cmd_vel_publishers_ ? "enabled" : "disabled"));
  controller_nh.param("base_frame_id", base_frame_id_, base_frame_id_);
  ROS_INFO_STREAM_NAMED(name_, "Base frame_id set to " << base_frame_id_);
  controller_nh.param("odom_frame_id", odom_frame_id_, odom_frame_id_);
  ROS_INFO_STREAM_NAMED(name_, "Odometry frame_id set to " << odom_frame_id_);
  controller_nh.param("enable_odom_tf", enable_odom_tf_, enable_odom_tf_);
  ROS_INFO_STREAM_NAMED(name_, "Publishing to tf is " << (enable_odom_tf_ ? "enabled" : "disabled"));

  // limits: min_* default to -max_*
  for (auto axis : {std::make_pair(std::string("linear/x/"), &limiter_lin_),
                    std::make_pair(std::string("angular/z/"), &limiter_ang_)})
  {
    const std::string& p = axis.first;
    SpeedLimiter& l = *axis.second;
    controller_nh.param(p + "has_velocity_limits", l.has_velocity_limits, l.has_velocity_limits);
    controller_nh.param(p + "has_acceleration_limits", l.has_acceleration_limits, l.has_acceleration_limits);
    controller_nh.param(p + "has_jerk_limits", l.has_jerk_limits, l.has_jerk_limits);
    controller_nh.param(p + "max_velocity", l.max_velocity, l.max_velocity);
    controller_nh.param(p + "min_velocity", l.min_velocity, -l.max_velocity);
    controller_nh.param(p + "max_acceleration", l.max_acceleration, l.max_acceleration);
    controller_nh.param(p + "min_acceleration", l.min_acceleration, -l.max_acceleration);
    controller_nh.param(p + "max_jerk", l.max_jerk, l.max_jerk);
    controller_nh.param(p + "min_jerk", l.min_jerk, -l.max_jerk);
  }

  controller_nh.param("publish_cmd", publish_cmd_, publish_cmd_);
  controller_nh.param("publish_wheel_joint_controller_state", publish_wheel_joint_controller_state_,
                      publish_wheel_joint_controller_state_);

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
    cmd_vel_pub_ = std::make_shared<realtime_tools::RealtimePublisher<geometry_msgs::TwistStamped>>(
        controller_nh, "cmd_vel_out", 100);

  if (publish_wheel_joint_controller_state_)
  {
    controller_state_pub_ = std::make_shared<realtime_tools::RealtimePublisher<control_msgs::JointTrajectoryControllerState>>(
        controller_nh, "wheel_joint_controller_state", 100);
    control_msgs::JointTrajectoryControllerState& msg = controller_state_pub_->msg_;
    const std::size_t num_wheels = wheel_joints_size_ * 2;
    msg.joint_names.resize(num_wheels);
    for (trajectory_msgs::JointTrajectoryPoint* point : {&msg.desired, &msg.actual, &msg.error})
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

  if (!setOdomPubFields(root_nh, controller_nh))
    return false;

  for (std::size_t i = 0; i < wheel_joints_size_; ++i)
  {
    ROS_INFO_STREAM_NAMED(name_, "Adding left wheel with joint name: " << left_wheel_names[i]
                                                                       << " and right wheel with joint name: "
                                                                       << right_wheel_names[i]);
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
  dyn_reconf_server_->setCallback(
      [this](DiffDriveControllerConfig& c, uint32_t level) { reconfCallback(c, level); });
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
    ROS_ERROR_STREAM_THROTTLE_NAMED(1.0, name_, "Detected " << sub_command_.getNumPublishers()
                                                            << " publishers. Only 1 publisher is allowed. Going to brake.");
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

bool DiffDriveController::getWheelNames(ros::NodeHandle& controller_nh, const std::string& wheel_param,
                                        std::vector<std::string>& wheel_names)
{
  XmlRpc::XmlRpcValue wheel_list;
  if (!controller_nh.getParam(wheel_param, wheel_list))
  {
    ROS_ERROR_STREAM_NAMED(name_, "Couldn't retrieve wheel param '" << wheel_param << "'.");
    return false;
  }
  if (wheel_list.getType() == XmlRpc::XmlRpcValue::TypeArray)
  {
    if (wheel_list.size() == 0)
    {
      ROS_ERROR_STREAM_NAMED(name_, "Wheel param '" << wheel_param << "' is an empty list");
      return false;
    }
    for (int i = 0; i < wheel_list.size(); ++i)
    {
      if (wheel_list[i].getType() != XmlRpc::XmlRpcValue::TypeString)
      {
        ROS_ERROR_STREAM_NAMED(name_, "Wheel param '" << wheel_param << "' #" << i << " isn't a string.");
        return false;
      }
    }
    wheel_names.resize(wheel_list.size());
    for (int i = 0; i < wheel_list.size(); ++i)
      wheel_names[i] = static_cast<std::string>(wheel_list[i]);
  }
  else if (wheel_list.getType() == XmlRpc::XmlRpcValue::TypeString)
  {
    wheel_names.push_back(static_cast<std::string>(wheel_list));
  }
  else
  {
    ROS_ERROR_STREAM_NAMED(name_, "Wheel param '" << wheel_param << "' is neither a list of strings nor a string.");
    return false;
  }
  return true;
}

bool DiffDriveController::setOdomParamsFromUrdf(ros::NodeHandle& root_nh, const std::string& left_wheel_name,
                                                 const std::string& right_wheel_name, bool lookup_wheel_separation,
                                                 bool lookup_wheel_radius)
{
  if (!(lookup_wheel_separation || lookup_wheel_radius))
    return true;  // both given as parameters: no URDF needed

  const std::string model_param_name = "robot_description";
  std::string robot_model_str;
  if (!root_nh.hasParam(model_param_name) || !root_nh.getParam(model_param_name, robot_model_str))
  {
    ROS_ERROR_NAMED(name_, "Robot description couldn't be retrieved from param server.");
    return false;
  }
  urdf::ModelInterfaceSharedPtr model(urdf::parseURDF(robot_model_str));
  if (!model)
  {
    ROS_ERROR_STREAM_NAMED(name_, "Could not parse the robot description ('" << root_nh.resolveName(model_param_name)
                                                                              << "').");
    return false;
  }

  urdf::JointConstSharedPtr left_wheel_joint(model->getJoint(left_wheel_name));
  urdf::JointConstSharedPtr right_wheel_joint(model->getJoint(right_wheel_name));
  if (!left_wheel_joint)
  {
    ROS_ERROR_STREAM_NAMED(name_, left_wheel_name << " couldn't be retrieved from model description");
    return false;
  }

  if (lookup_wheel_separation)
  {
    if (!right_wheel_joint)
    {
      ROS_ERROR_STREAM_NAMED(name_, right_wheel_name << " couldn't be retrieved from model description");
      return false;
    }
    const urdf::Vector3& l = left_wheel_joint->parent_to_joint_origin_transform.position;
    const urdf::Vector3& r = right_wheel_joint->parent_to_joint_origin_transform.position;
    ROS_INFO_STREAM("left wheel to origin: " << l.x << "," << l.y << ", " << l.z);
    ROS_INFO_STREAM("right wheel to origin: " << r.x << "," << r.y << ", " << r.z);
    wheel_separation_ = euclideanOfVectors(l, r);
  }

  if (lookup_wheel_radius)
  {
    if (!getWheelRadius(model->getLink(left_wheel_joint->child_link_name), wheel_radius_))
    {
      ROS_ERROR_STREAM_NAMED(name_, "Couldn't retrieve " << left_wheel_name << " wheel radius");
      return false;
    }
  }
  return true;
}

bool DiffDriveController::setOdomPubFields(ros::NodeHandle& root_nh, ros::NodeHandle& controller_nh)
{
  double pose_cov[6], twist_cov[6];
  if (!getCovarianceDiagonal(controller_nh, "pose_covariance_diagonal", name_, pose_cov) ||
      !getCovarianceDiagonal(controller_nh, "twist_covariance_diagonal", name_, twist_cov))
    return false;

  odom_pub_ = std::make_shared<realtime_tools::RealtimePublisher<nav_msgs::Odometry>>(controller_nh, "odom", 100);
  nav_msgs::Odometry& odom = odom_pub_->msg_;
  odom.header.frame_id = odom_frame_id_;
  odom.child_frame_id = base_frame_id_;
  odom.pose.pose.position.z = 0;
  odom.twist.twist.linear.y = 0;
  odom.twist.twist.linear.z = 0;
  odom.twist.twist.angular.x = 0;
  odom.twist.twist.angular.y = 0;
  for (int i = 0; i < 36; ++i)
  {
    odom.pose.covariance[i] = 0.0;
    odom.twist.covariance[i] = 0.0;
  }
  for (int i = 0; i < 6; ++i)
  {
    odom.pose.covariance[i * 7] = pose_cov[i];
    odom.twist.covariance[i * 7] = twist_cov[i];
  }

  tf_odom_pub_ = std::make_shared<realtime_tools::RealtimePublisher<tf2_msgs::TFMessage>>(root_nh, "/tf", 100);
  tf_odom_pub_->msg_.transforms.resize(1);
  tf_odom_pub_->msg_.transforms[0].transform.translation.z = 0.0;
  tf_odom_pub_->msg_.transforms[0].child_frame_id = base_frame_id_;
  tf_odom_pub_->msg_.transforms[0].header.frame_id = odom_frame_id_;
  return true;
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
  ROS_INFO_STREAM_NAMED(name_, "Dynamic Reconfigure:\n"
                                   << "Left wheel radius multiplier: " << dynamic_params.left_wheel_radius_multiplier
                                   << "\nRight wheel radius multiplier: "
                                   << dynamic_params.right_wheel_radius_multiplier
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

void DiffDriveController::publishWheelData(const ros::Time& time, const ros::Duration& period,
                                           const Commands& curr_cmd, double wheel_separation,
                                           double left_wheel_radius, double right_wheel_radius)
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
    const hardware_interface::JointHandle* joints[2] = {&left_wheel_joints_[i], &right_wheel_joints_[i]};
    std::vector<double>* previous[2] = {&vel_left_previous_, &vel_right_previous_};
    const double desired[2] = {vel_left_desired, vel_right_desired};
    const double desired_previous[2] = {vel_left_desired_previous_, vel_right_desired_previous_};
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
