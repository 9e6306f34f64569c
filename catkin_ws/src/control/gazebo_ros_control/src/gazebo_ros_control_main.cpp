// gazebo_ros_control_node [--estop-topic TOPIC] [--parent-pid PID]  (in the robot namespace:
// __ns:=NS). ode_sim's libgazebo_ros_control.so starts it for every model that loads the
// plugin; it can also be started by hand against a running simulator.
#include <cstdlib>
#include <cstring>
#include <string>

#include <ros/ros.h>

#include <gazebo_ros_control/gazebo_ros_control_node.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "gazebo_ros_control");
  gazebo_ros_control::GazeboRosControlNode::Options options;
  std::vector<std::string> args;
  ros::removeROSArgs(argc, argv, args);
  for (std::size_t i = 1; i < args.size(); ++i)
  {
    if (args[i] == "--estop-topic" && i + 1 < args.size())
      options.estop_topic = args[++i];
    else if (args[i] == "--parent-pid" && i + 1 < args.size())
      options.parent_pid = std::atoi(args[++i].c_str());
    else
    {
      ROS_FATAL(
          "gazebo_ros_control_node: unknown argument '%s' (usage: gazebo_ros_control_node "
          "[--estop-topic TOPIC] [--parent-pid PID] __ns:=ROBOT_NAMESPACE)",
          args[i].c_str());
      return 2;
    }
  }
  ros::NodeHandle model_nh;  // the node's namespace = the robot namespace
  gazebo_ros_control::GazeboRosControlNode node(model_nh, options);
  std::string error;
  if (!node.init(&error))
  {
    ROS_FATAL_STREAM("gazebo_ros_control: " << error);
    return 1;
  }
  node.run();
  return 0;
}
