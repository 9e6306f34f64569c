// libgazebo_ros_control_inprocess.so: GazeboRosControlNode inside the simulator's process,
// for ode_sim's <controllerNode>inprocess</controllerNode> (loaded with ctypes). The simulator
// calls grc_update() once per control period with the joints' state and applies the commands
// it returns: no topics, no waiting, as gazebo_ros_control runs inside gzserver.
#include <cstring>
#include <mutex>
#include <string>

#include <ros/ros.h>

#include <gazebo_ros_control/gazebo_ros_control_node.h>

namespace
{
std::mutex g_lock;
int g_instances = 0;

void copyError(const std::string& text, char* error, int error_len)
{
  if (error && error_len > 0)
  {
    std::strncpy(error, text.c_str(), static_cast<std::size_t>(error_len - 1));
    error[error_len - 1] = '\0';
  }
}
}  // namespace

extern "C"
{
  /// A controller manager in namespace `ns` over the joints of NS/ode_sim/joints. NULL on error
  /// (the reason in `error`).
  void* grc_create(const char* ns, const char* estop_topic, char* error, int error_len)
  {
    std::lock_guard<std::mutex> guard(g_lock);
    if (!ros::isInitialized())
    {
      // the simulator hands the sim time to every grc_update() (ros::Time::setNow), so this
      // roscpp does not subscribe to the /clock its own process publishes (with /use_sim_time
      // ros::start() would: a thousand messages a wall second received over TCP, at many times
      // real time, for a time it already has)
      ros::M_string remappings;
      remappings["/clock"] = "/gazebo/inprocess_clock_unused";
      ros::init(remappings, "gazebo_ros_control",
                ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
    }
    gazebo_ros_control::GazeboRosControlNode::Options options;
    options.estop_topic = estop_topic ? estop_topic : "";
    options.in_process = true;
    options.wait_for_joints = 5.0;
    auto* node = new gazebo_ros_control::GazeboRosControlNode(ros::NodeHandle(ns ? ns : "/"), options);
    std::string why;
    if (!node->init(&why))
    {
      delete node;
      copyError(why, error, error_len);
      return nullptr;
    }
    ++g_instances;
    return node;
  }

  /// Number of joints (the length of the arrays of grc_update).
  int grc_size(void* handle)
  {
    return static_cast<int>(static_cast<gazebo_ros_control::GazeboRosControlNode*>(handle)->size());
  }

  /// One control period at sim time `stamp_ns`: state in, commands out (NaN: keep the previous).
  void grc_update(void* handle, long long stamp_ns, const double* position, const double* velocity,
                  const double* effort, double* command)
  {
    ros::Time t;
    t.fromNSec(static_cast<uint64_t>(stamp_ns));
    if (ros::Time::isSimTime())
      ros::Time::setNow(t);  // what the /clock subscription did (see grc_create)
    static_cast<gazebo_ros_control::GazeboRosControlNode*>(handle)->stepDirect(t, position, velocity, effort, command);
  }

  void grc_destroy(void* handle)
  {
    std::lock_guard<std::mutex> guard(g_lock);
    // the last one: stop roscpp first (ros::ok() turns false), so that a controller switch
    // waiting for an update that will never come gives up, and the simulator's process exits
    if (--g_instances == 0 && ros::isStarted())
      ros::shutdown();
    delete static_cast<gazebo_ros_control::GazeboRosControlNode*>(handle);
  }

}  // extern "C"
