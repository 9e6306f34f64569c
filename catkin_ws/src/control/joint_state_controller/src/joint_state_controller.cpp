#include <joint_state_controller/joint_state_controller.h>

#include <algorithm>

#include <hardware_interface/hardware_interface_exception.h>
#include <pluginlib/class_list_macros.hpp>

namespace joint_state_controller
{
namespace
{
bool isNumber(XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeDouble || value.getType() == XmlRpc::XmlRpcValue::TypeInt;
}

double toDouble(XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeInt ? static_cast<double>(static_cast<int>(value))
                                                         : static_cast<double>(value);
}
}  // namespace

bool JointStateController::init(hardware_interface::JointStateInterface* hw, ros::NodeHandle& root_nh,
                                ros::NodeHandle& controller_nh)
{
  std::vector<std::string> joint_names;
  if (controller_nh.hasParam("joints"))
  {
    if (!controller_nh.getParam("joints", joint_names))
    {
      ROS_ERROR("Parameter 'joints' is not a list of joint names (namespace: %s)",
                controller_nh.getNamespace().c_str());
      return false;
    }
  }
  else
  {
    joint_names = hw->getNames();
  }
  num_hw_joints_ = joint_names.size();
  for (const std::string& name : joint_names)
    ROS_DEBUG("Got joint %s", name.c_str());

  if (!controller_nh.getParam("publish_rate", publish_rate_))
  {
    ROS_ERROR("Parameter 'publish_rate' not set");
    return false;
  }

  joint_state_.clear();
  for (const std::string& name : joint_names)
  {
    try
    {
      joint_state_.push_back(hw->getHandle(name));
    }
    catch (const hardware_interface::HardwareInterfaceException& e)
    {
      ROS_ERROR("Could not get joint '%s' (namespace: %s): %s", name.c_str(), controller_nh.getNamespace().c_str(),
                e.what());
      return false;
    }
  }

  // queue 100 (the original: 4): at many times real time a busy machine's roscpp writes a burst
  // of joint states late, and 4 per subscriber dropped 1-2 % of them (bench/sim_rtf --launch)
  realtime_pub_ =
      std::make_shared<realtime_tools::RealtimePublisher<sensor_msgs::JointState>>(root_nh, "joint_states", 100);
  // msg_ is not shared with the publishing thread until the first unlockAndPublish()
  sensor_msgs::JointState& msg = realtime_pub_->msg_;
  for (const std::string& name : joint_names)
  {
    msg.name.push_back(name);
    msg.position.push_back(0.0);
    msg.velocity.push_back(0.0);
    msg.effort.push_back(0.0);
  }
  addExtraJoints(controller_nh, msg);
  return true;
}

void JointStateController::starting(const ros::Time& time) { last_publish_time_ = time; }

void JointStateController::update(const ros::Time& time, const ros::Duration& /*period*/)
{
  if (publish_rate_ > 0.0 && last_publish_time_ + ros::Duration(1.0 / publish_rate_) < time)
  {
    if (realtime_pub_->trylock())
    {
      last_publish_time_ = last_publish_time_ + ros::Duration(1.0 / publish_rate_);
      sensor_msgs::JointState& msg = realtime_pub_->msg_;
      msg.header.stamp = time;
      for (unsigned int i = 0; i < num_hw_joints_; ++i)
      {
        msg.position[i] = joint_state_[i].getPosition();
        msg.velocity[i] = joint_state_[i].getVelocity();
        msg.effort[i] = joint_state_[i].getEffort();
      }
      realtime_pub_->unlockAndPublish();
    }
  }
}

void JointStateController::stopping(const ros::Time& /*time*/) {}

void JointStateController::addExtraJoints(const ros::NodeHandle& nh, sensor_msgs::JointState& msg)
{
  XmlRpc::XmlRpcValue list;
  if (!nh.getParam("extra_joints", list))
  {
    ROS_DEBUG("No extra joints specification found.");
    return;
  }
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray)
  {
    ROS_ERROR("Extra joints specification is not an array. Ignoring.");
    return;
  }
  for (int i = 0; i < list.size(); ++i)
  {
    XmlRpc::XmlRpcValue& joint = list[i];
    if (joint.getType() != XmlRpc::XmlRpcValue::TypeStruct)
    {
      ROS_ERROR_STREAM("Extra joint specification is not a struct, but rather '" << joint.getType() << "'. Ignoring.");
      continue;
    }
    if (!joint.hasMember("name") || joint["name"].getType() != XmlRpc::XmlRpcValue::TypeString)
    {
      ROS_ERROR_STREAM("Extra joint does not specify name. Ignoring.");
      continue;
    }
    const std::string name = joint["name"];
    if (std::find(msg.name.begin(), msg.name.end(), name) != msg.name.end())
    {
      ROS_WARN_STREAM("Joint state interface already contains specified extra joint '" << name << "'.");
      continue;
    }
    double values[3] = { 0.0, 0.0, 0.0 };
    const char* fields[3] = { "position", "velocity", "effort" };
    bool valid = true;
    for (int k = 0; k < 3 && valid; ++k)
    {
      if (!joint.hasMember(fields[k]))
        continue;
      if (!isNumber(joint[fields[k]]))
      {
        ROS_ERROR_STREAM("Extra joint '" << name << "' does not specify a valid default " << fields[k]
                                         << ". Ignoring.");
        valid = false;
        break;
      }
      values[k] = toDouble(joint[fields[k]]);
    }
    if (!valid)
      continue;
    msg.name.push_back(name);
    msg.position.push_back(values[0]);
    msg.velocity.push_back(values[1]);
    msg.effort.push_back(values[2]);
  }
}

}  // namespace joint_state_controller

PLUGINLIB_EXPORT_CLASS(joint_state_controller::JointStateController, controller_interface::ControllerBase)
