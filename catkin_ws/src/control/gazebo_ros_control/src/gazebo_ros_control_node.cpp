#include <gazebo_ros_control/gazebo_ros_control_node.h>

#include <unistd.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace gazebo_ros_control
{

namespace
{
bool number(XmlRpc::XmlRpcValue& v, double* out)
{
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble)
    *out = static_cast<double>(v);
  else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt)
    *out = static_cast<int>(v);
  else
    return false;
  return std::isfinite(*out);
}

std::string joinNs(const std::string& ns, const std::string& name)
{
  if (!name.empty() && name[0] == '/')
    return name;
  if (ns.empty() || ns == "/")
    return "/" + name;
  return ns + "/" + name;
}
}  // namespace

GazeboRosControlNode::GazeboRosControlNode(const ros::NodeHandle& model_nh, const Options& options)
  : model_nh_(model_nh), options_(options), robot_namespace_(model_nh.getNamespace())
{
}

bool GazeboRosControlNode::parseJoints(XmlRpc::XmlRpcValue& value, const std::string& param,
                                       std::vector<BridgeJoint>* joints, std::string* error)
{
  joints->clear();
  if (value.getType() != XmlRpc::XmlRpcValue::TypeArray)
  {
    *error = param + " must be a list of joints (dicts with name, interface, ...)";
    return false;
  }
  for (int i = 0; i < value.size(); ++i)
  {
    XmlRpc::XmlRpcValue& e = value[i];
    std::ostringstream where;
    where << param << "[" << i << "]";
    if (e.getType() != XmlRpc::XmlRpcValue::TypeStruct || !e.hasMember("name") ||
        e["name"].getType() != XmlRpc::XmlRpcValue::TypeString || !e.hasMember("interface") ||
        e["interface"].getType() != XmlRpc::XmlRpcValue::TypeString)
    {
      *error = where.str() + " must be a dict with string 'name' and 'interface'";
      return false;
    }
    BridgeJoint j;
    j.name = static_cast<std::string>(e["name"]);
    const std::string iface = static_cast<std::string>(e["interface"]);
    if (!parseJointInterface(iface, &j.interface))
    {
      *error = where.str() + " (joint '" + j.name + "'): unknown interface '" + iface + "'";
      return false;
    }
    const char* numeric[] = { "reduction", "lower", "upper", "effort", "velocity" };
    double values[5] = { 1.0, 0.0, 0.0, 0.0, 0.0 };
    bool present[5] = { false, false, false, false, false };
    for (int k = 0; k < 5; ++k)
    {
      if (!e.hasMember(numeric[k]))
        continue;
      if (!number(e[numeric[k]], &values[k]))
      {
        *error = where.str() + " (joint '" + j.name + "'): '" + numeric[k] + "' must be a finite number";
        return false;
      }
      present[k] = true;
    }
    j.reduction = values[0];
    if (present[1] != present[2])
    {
      *error = where.str() + " (joint '" + j.name + "'): 'lower' and 'upper' come together";
      return false;
    }
    j.has_position_limits = present[1] && values[2] >= values[1];
    j.lower = values[1];
    j.upper = values[2];
    j.has_effort_limit = present[3] && values[3] > 0.0;
    j.effort = values[3];
    j.has_velocity_limit = present[4] && values[4] > 0.0;
    j.velocity = values[4];
    joints->push_back(j);
  }
  return true;
}

/// The simulator's joint list parameter, waited for (wall time) up to wait_s; false with the
/// reason in *error when it does not come.
static bool waitForJointsParam(const std::string& joints_param, double wait_s, const std::string& robot_namespace,
                               XmlRpc::XmlRpcValue& joints_value, std::string* error)
{
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(wait_s);
  bool warned = false;
  while (!ros::param::get(joints_param, joints_value))
  {
    if (!ros::ok() || ros::WallTime::now() > deadline)
    {
      *error = "parameter " + joints_param +
               " not set: is ode_sim running a model whose URDF loads libgazebo_ros_control.so "
               "in namespace '" +
               robot_namespace + "'?";
      return false;
    }
    if (!warned)
    {
      ROS_INFO_STREAM("gazebo_ros_control: waiting for " << joints_param);
      warned = true;
    }
    ros::WallDuration(0.1).sleep();
  }
  return true;
}

bool GazeboRosControlNode::init(std::string* error)
{
  const std::string joints_param = joinNs(robot_namespace_, "ode_sim/joints");
  const std::string period_param = joinNs(robot_namespace_, "ode_sim/control_period");
  XmlRpc::XmlRpcValue joints_value;
  if (!waitForJointsParam(joints_param, options_.wait_for_joints, robot_namespace_, joints_value, error))
    return false;
  std::vector<BridgeJoint> joints;
  if (!parseJoints(joints_value, joints_param, &joints, error))
    return false;
  double period = 0.0;
  if (!ros::param::get(period_param, period) || !(period > 0.0))
  {
    *error = "parameter " + period_param + " must be a positive number of seconds";
    return false;
  }
  control_period_ = period;

  model_.reset(new BridgeModel(joints));
  robot_hw_sim_.reset(new DefaultRobotHWSim());
  if (!robot_hw_sim_->initSim(robot_namespace_, model_nh_, model_.get()))
  {
    *error = "Could not initialize robot simulation interface";
    return false;
  }
  controller_manager_.reset(new controller_manager::ControllerManager(robot_hw_sim_.get(), model_nh_));
  // a paused world calls no update(): a switch requested meanwhile waits for the world to run,
  // however long (as with Gazebo's own plugin), instead of being withdrawn after 30 s
  controller_manager_->setSwitchWaitTimeout(0.0);

  if (options_.estop_topic.size())
    estop_sub_ = model_nh_.subscribe(options_.estop_topic, 1, &GazeboRosControlNode::estopCallback, this);
  if (options_.in_process)
  {
    spinner_.reset(new ros::AsyncSpinner(1));
    spinner_->start();
    ROS_INFO_STREAM("gazebo_ros_control: controller manager in namespace '"
                    << (robot_namespace_.empty() ? "/" : robot_namespace_) << "' inside the simulator, "
                    << joints.size() << " joint(s), control period " << control_period_ << " s");
    return true;
  }

  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const BridgeJoint& j : joints)
  {
    if (j.interface == JointInterface::STATE)
      continue;
    command_msg_.name.push_back(j.name);
  }
  command_msg_.position.assign(command_msg_.name.size(), nan);
  command_msg_.velocity.assign(command_msg_.name.size(), nan);
  command_msg_.effort.assign(command_msg_.name.size(), nan);
  command_pub_ = model_nh_.advertise<sensor_msgs::JointState>("ode_sim/joint_commands", 10);

  ros::SubscribeOptions so = ros::SubscribeOptions::create<sensor_msgs::JointState>(
      "ode_sim/joint_states", 10, [this](const sensor_msgs::JointStateConstPtr& m) { stateCallback(m); },
      ros::VoidPtr(), &state_queue_);
  so.transport_hints = ros::TransportHints().tcpNoDelay();
  state_sub_ = model_nh_.subscribe(so);

  ROS_INFO_STREAM("gazebo_ros_control: controller manager in namespace '"
                  << (robot_namespace_.empty() ? "/" : robot_namespace_) << "', " << joints.size()
                  << " joint(s), control period " << control_period_ << " s"
                  << (options_.estop_topic.empty() ? "" : ", e-stop on " + options_.estop_topic));
  return true;
}

bool GazeboRosControlNode::parentAlive() const { return options_.parent_pid <= 0 || getppid() == options_.parent_pid; }

void GazeboRosControlNode::run()
{
  // controller_manager services block until update() runs the switch: they need a thread of
  // their own, apart from the queue that drives update()
  ros::AsyncSpinner spinner(1);
  spinner.start();
  while (ros::ok())
  {
    state_queue_.callAvailable(ros::WallDuration(0.1));
    if (!parentAlive())
    {
      ROS_INFO("gazebo_ros_control: the simulator (pid %d) is gone; exiting", options_.parent_pid);
      break;
    }
  }
  spinner.stop();
}

void GazeboRosControlNode::estopCallback(const std_msgs::BoolConstPtr& msg) { e_stop_active_ = msg->data; }

void GazeboRosControlNode::stateCallback(const sensor_msgs::JointStateConstPtr& msg)
{
  std::string error;
  if (!model_->setState(msg->name, msg->position, msg->velocity, msg->effort, &error))
  {
    ++bad_states_;
    ROS_WARN_THROTTLE(1.0, "gazebo_ros_control: %s/ode_sim/joint_states: %s; cycle skipped (%lu so far)",
                      robot_namespace_.c_str(), error.c_str(), bad_states_);
    return;
  }
  update(msg->header.stamp);

  std::size_t k = 0;
  for (std::size_t j = 0; j < model_->size(); ++j)
  {
    const JointInterface iface = model_->joints()[j].interface;
    if (iface == JointInterface::STATE)
      continue;
    const double cmd = model_->command(j);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    command_msg_.effort[k] = iface == JointInterface::EFFORT ? cmd : nan;
    command_msg_.velocity[k] = iface == JointInterface::VELOCITY ? cmd : nan;
    command_msg_.position[k] = iface == JointInterface::POSITION ? cmd : nan;
    ++k;
  }
  command_msg_.header.stamp = msg->header.stamp;
  command_pub_.publish(command_msg_);
}

void GazeboRosControlNode::stepDirect(const ros::Time& t, const double* position, const double* velocity,
                                      const double* effort, double* command)
{
  const std::size_t n = model_->size();
  model_->setState(position, velocity, effort);
  update(t);
  for (std::size_t j = 0; j < n; ++j)
    command[j] = model_->joints()[j].interface == JointInterface::STATE ? std::numeric_limits<double>::quiet_NaN()
                                                                        : model_->command(j);
}

void GazeboRosControlNode::update(const ros::Time& t)
{
  ros::Duration period(control_period_);
  if (have_last_update_ && t > last_update_)
    period = t - last_update_;
  last_update_ = t;
  have_last_update_ = true;

  const bool e_stop = e_stop_active_;
  bool reset_controllers = false;
  if (e_stop)
    last_e_stop_active_ = true;
  else if (last_e_stop_active_)
  {
    reset_controllers = true;
    last_e_stop_active_ = false;
  }
  robot_hw_sim_->eStopActive(e_stop);
  robot_hw_sim_->readSim(t, period);
  controller_manager_->update(t, period, reset_controllers);
  robot_hw_sim_->writeSim(t, period);
}

}  // namespace gazebo_ros_control
