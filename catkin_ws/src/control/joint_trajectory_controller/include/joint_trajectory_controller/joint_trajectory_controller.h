// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <control_msgs/QueryTrajectoryState.h>
#include <controller_interface/controller.h>
#include <realtime_tools/realtime_publisher.h>
#include <ros/node_handle.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <joint_trajectory_controller/hardware_interface_adapter.h>
#include <joint_trajectory_controller/init_joint_trajectory.h>
#include <joint_trajectory_controller/joint_trajectory_segment.h>
#include <joint_trajectory_controller/tolerances.h>

namespace joint_trajectory_controller
{
/**
 * \brief Executes joint-space trajectories on a set of joints (ros_controllers' controller).
 *
 * ROS API, in the controller's namespace:
 * - action \c follow_joint_trajectory (control_msgs/FollowJointTrajectory);
 * - topic \c command (trajectory_msgs/JointTrajectory): replaces the future part of the current
 *   trajectory; an empty one stops the joints;
 * - topic \c state (control_msgs/JointTrajectoryControllerState) at \c state_publish_rate;
 * - service \c query_state (control_msgs/QueryTrajectoryState).
 * Parameters: \c joints, \c constraints/…, \c gains/<joint>/… and \c velocity_ff/<joint> (velocity
 * and effort interfaces), \c stop_trajectory_duration (0), \c state_publish_rate (50),
 * \c action_monitor_rate (20), \c allow_partial_joints_goal (false); continuous joints of
 * \c robot_description wrap around.
 *
 * \tparam SegmentImpl segment type, e.g. trajectory_interface::QuinticSplineSegment<double>
 * \tparam HardwareInterface the command interface (see HardwareInterfaceAdapter)
 */
template <class SegmentImpl, class HardwareInterface>
class JointTrajectoryController : public controller_interface::Controller<HardwareInterface>
{
public:
  typedef SegmentImpl Segment;
  typedef typename Segment::Scalar Scalar;
  typedef typename Segment::State State;
  typedef joint_trajectory_controller::SegmentsPerJoint<Segment> Trajectory;
  typedef std::shared_ptr<const Trajectory> TrajectoryPtr;
  typedef actionlib::ActionServer<control_msgs::FollowJointTrajectoryAction> ActionServer;
  typedef ActionServer::GoalHandle GoalHandle;
  typedef typename HardwareInterface::ResourceHandleType JointHandle;
  typedef HardwareInterfaceAdapter<HardwareInterface, State> HwIfaceAdapter;

  JointTrajectoryController() = default;
  ~JointTrajectoryController() override;

  bool init(HardwareInterface* hw, ros::NodeHandle& root_nh, ros::NodeHandle& controller_nh) override;
  void starting(const ros::Time& time) override;
  void stopping(const ros::Time& time) override;
  void update(const ros::Time& time, const ros::Duration& period) override;

protected:
  /// Replace the future of the current trajectory with \p msg (empty: stop). Non-realtime.
  bool updateTrajectoryCommand(const trajectory_msgs::JointTrajectory& msg, const GoalTrackerPtr& goal,
                               const SegmentTolerances<Scalar>& tolerances, TrajectoryError& error);
  /// Stop the joints (stop_trajectory_duration ramp, or at once at the actual position). Non-realtime.
  void setHoldPosition(const ros::Time& time, const GoalTrackerPtr& goal = GoalTrackerPtr());
  void trajectoryCommandCB(const trajectory_msgs::JointTrajectoryConstPtr& msg);
  void goalCB(GoalHandle gh);
  void cancelCB(GoalHandle gh);
  bool queryStateService(control_msgs::QueryTrajectoryState::Request& req,
                         control_msgs::QueryTrajectoryState::Response& resp);
  void monitorGoals(const ros::TimerEvent&);
  void preemptActiveGoal();
  TrajectoryPtr currentTrajectory() const;
  void setTrajectory(const TrajectoryPtr& traj);
  ros::Time lastUpdateTime() const { return ros::Time().fromNSec(last_update_nsec_.load()); }

  std::string name_;
  std::vector<JointHandle> joints_;
  std::vector<std::string> joint_names_;
  std::vector<bool> angle_wraparound_;
  SegmentTolerances<Scalar> default_tolerances_;
  HwIfaceAdapter hw_iface_adapter_;

  ros::NodeHandle controller_nh_;
  ros::Subscriber trajectory_command_sub_;
  std::shared_ptr<ActionServer> action_server_;
  ros::ServiceServer query_state_service_;
  ros::Timer goal_handle_timer_;
  std::shared_ptr<realtime_tools::RealtimePublisher<control_msgs::JointTrajectoryControllerState>> state_publisher_;

  double stop_trajectory_duration_ = 0.0;
  double state_publish_period_ = 0.02;
  double action_monitor_period_ = 0.05;
  bool allow_partial_joints_goal_ = false;

  mutable std::mutex trajectory_mutex_;  // guards curr_trajectory_ (pointer swap only)
  TrajectoryPtr curr_trajectory_;
  std::mutex goal_mutex_;  // non-realtime: guards active_goal_
  GoalTrackerPtr active_goal_;
  std::atomic<int64_t> last_update_nsec_{ 0 };
  ros::Time last_state_publish_time_;

  // Realtime scratch (sized in init).
  State current_state_, desired_state_, state_error_, desired_joint_state_, hold_state_;
  std::mutex feedback_mutex_;  // try-locked by the loop; guards feedback_
  control_msgs::FollowJointTrajectoryFeedback feedback_;
  bool feedback_valid_ = false;
};

}  // namespace joint_trajectory_controller

#include <joint_trajectory_controller/joint_trajectory_controller_impl.h>
