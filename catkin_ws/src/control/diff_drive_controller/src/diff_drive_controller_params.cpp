// DiffDriveController's parameters: the wheel names, the wheel geometry from the URDF, the
// odometry publishers' fixed fields, and the odometry and command parameters read by init().
#include <diff_drive_controller/diff_drive_controller.h>

#include <cmath>

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

}  // namespace

/// Odometry parameters (open loop, multipliers, rolling window); the state publish rate [Hz].
double DiffDriveController::readOdometryParams(ros::NodeHandle& controller_nh)
{
  double publish_rate = 50.0;
  controller_nh.param("publish_rate", publish_rate, publish_rate);
  ROS_INFO_STREAM_NAMED(name_, "Controller state will be published at " << publish_rate << "Hz.");

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
  return publish_rate;
}

/// Command parameters: timeout, publishers, frames, tf, speed limits, optional publishers.
void DiffDriveController::readCommandParams(ros::NodeHandle& controller_nh)
{
  controller_nh.param("cmd_vel_timeout", cmd_vel_timeout_, cmd_vel_timeout_);
  ROS_INFO_STREAM_NAMED(name_,
                        "Velocity commands will be considered old if they are older than " << cmd_vel_timeout_ << "s.");
  controller_nh.param("allow_multiple_cmd_vel_publishers", allow_multiple_cmd_vel_publishers_,
                      allow_multiple_cmd_vel_publishers_);
  ROS_INFO_STREAM_NAMED(
      name_, "Allow mutiple cmd_vel publishers is " << (allow_multiple_cmd_vel_publishers_ ? "enabled" : "disabled"));
  controller_nh.param("base_frame_id", base_frame_id_, base_frame_id_);
  ROS_INFO_STREAM_NAMED(name_, "Base frame_id set to " << base_frame_id_);
  controller_nh.param("odom_frame_id", odom_frame_id_, odom_frame_id_);
  ROS_INFO_STREAM_NAMED(name_, "Odometry frame_id set to " << odom_frame_id_);
  controller_nh.param("enable_odom_tf", enable_odom_tf_, enable_odom_tf_);
  ROS_INFO_STREAM_NAMED(name_, "Publishing to tf is " << (enable_odom_tf_ ? "enabled" : "disabled"));

  // limits: min_* default to -max_*
  for (auto axis : { std::make_pair(std::string("linear/x/"), &limiter_lin_),
                     std::make_pair(std::string("angular/z/"), &limiter_ang_) })
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
    ROS_ERROR_STREAM_NAMED(
        name_, "Could not parse the robot description ('" << root_nh.resolveName(model_param_name) << "').");
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

}  // namespace diff_drive_controller
