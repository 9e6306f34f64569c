// The controller side of ode_sim's ros_control bridge (ode_sim/doc/ros_control_bridge.md), in
// the place of gazebo_ros_control's GazeboRosControlPlugin: reads NS/ode_sim/joints and
// NS/ode_sim/control_period, runs DefaultRobotHWSim and a controller_manager in NS and, on
// every NS/ode_sim/joint_states message (time t_k): readSim(); cm.update(t_k, period);
// writeSim(); publishes NS/ode_sim/joint_commands stamped t_k (the simulator's lockstep waits
// for it). Controller manager services run on an AsyncSpinner; the update loop has a
// callback queue of its own.
#ifndef GAZEBO_ROS_CONTROL_GAZEBO_ROS_CONTROL_NODE_H
#define GAZEBO_ROS_CONTROL_GAZEBO_ROS_CONTROL_NODE_H

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <controller_manager/controller_manager.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Bool.h>

#include <gazebo_ros_control/bridge_model.h>
#include <gazebo_ros_control/default_robot_hw_sim.h>

namespace gazebo_ros_control
{

class GazeboRosControlNode
{
public:
  struct Options
  {
    std::string estop_topic;        ///< relative to NS; empty = no e-stop
    int parent_pid = 0;             ///< exit when this process is no longer the parent (0: never)
    double wait_for_joints = 30.0;  ///< [s, wall] to wait for NS/ode_sim/joints
    /// inside the simulator's process: no bridge topics, the simulator calls stepDirect()
    /// every control period; the services get an AsyncSpinner of their own from init()
    bool in_process = false;
  };

  GazeboRosControlNode(const ros::NodeHandle& model_nh, const Options& options);

  /// Reads the bridge parameters and builds the hardware and the controller manager.
  /// Returns false with a one-line reason in *error.
  bool init(std::string* error);

  /// Runs until ROS shuts down or the parent process (the simulator) is gone.
  void run();

  /// Parses NS/ode_sim/joints. Errors name `param` and the entry.
  static bool parseJoints(XmlRpc::XmlRpcValue& value, const std::string& param, std::vector<BridgeJoint>* joints,
                          std::string* error);

  /// One control period: state in, controllers, command out (also used by tests).
  void stateCallback(const sensor_msgs::JointStateConstPtr& msg);

  /// In-process control period at sim time t: the joints' state in NS/ode_sim/joints order
  /// in, their commands out (NaN: none yet, or a state-only joint). Arrays of size().
  void stepDirect(const ros::Time& t, const double* position, const double* velocity, const double* effort,
                  double* command);

  std::size_t size() const { return model_ ? model_->size() : 0; }

private:
  void update(const ros::Time& t);
  void estopCallback(const std_msgs::BoolConstPtr& msg);
  bool parentAlive() const;

  ros::NodeHandle model_nh_;
  Options options_;
  std::string robot_namespace_;
  double control_period_ = 0.001;

  std::unique_ptr<BridgeModel> model_;
  std::unique_ptr<DefaultRobotHWSim> robot_hw_sim_;
  std::unique_ptr<controller_manager::ControllerManager> controller_manager_;

  std::unique_ptr<ros::AsyncSpinner> spinner_;
  ros::CallbackQueue state_queue_;
  ros::Subscriber state_sub_;
  ros::Subscriber estop_sub_;
  ros::Publisher command_pub_;
  sensor_msgs::JointState command_msg_;

  ros::Time last_update_;
  bool have_last_update_ = false;
  std::atomic<bool> e_stop_active_{ false };
  bool last_e_stop_active_ = false;
  unsigned long bad_states_ = 0;
};

}  // namespace gazebo_ros_control

#endif  // GAZEBO_ROS_CONTROL_GAZEBO_ROS_CONTROL_NODE_H
