// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <algorithm>
#include <cmath>
#include <sstream>

#include <angles/angles.h>
#include <ros/console.h>
#include <ros/names.h>
#include <ros/param.h>
#include <urdf/model.h>

#include <joint_trajectory_controller/internal/controller_helpers.h>

namespace joint_trajectory_controller
{

template <class SegmentImpl, class HardwareInterface>
JointTrajectoryController<SegmentImpl, HardwareInterface>::~JointTrajectoryController()
{
  goal_handle_timer_.stop();
  trajectory_command_sub_.shutdown();
  query_state_service_.shutdown();
  action_server_.reset();
}

template <class SegmentImpl, class HardwareInterface>
bool JointTrajectoryController<SegmentImpl, HardwareInterface>::init(HardwareInterface* hw, ros::NodeHandle& root_nh,
                                                                     ros::NodeHandle& controller_nh)
{
  controller_nh_ = controller_nh;
  name_ = internal::controllerName(controller_nh_);

  if (!controller_nh_.getParam("joints", joint_names_) || joint_names_.empty())
  {
    ROS_ERROR_STREAM_NAMED(name_, "Could not find joint names (a non-empty list) in parameter '"
                                      << controller_nh_.getNamespace() << "/joints'.");
    return false;
  }
  const unsigned int n_joints = joint_names_.size();

  // Continuous joints of the robot description wrap around. As the original: the description in
  // the controller manager's namespace, else the nearest 'robot_description' above it.
  std::string urdf_string, urdf_param;
  if (!internal::robotDescription(root_nh, name_, urdf_string, urdf_param))
    return false;
  urdf::Model urdf;
  if (!urdf.initString(urdf_string))
  {
    ROS_ERROR_STREAM_NAMED(name_, "Failed to parse URDF contained in '" << urdf_param << "' parameter");
    return false;
  }
  if (!internal::jointHandles(hw, urdf, joint_names_, name_, angle_wraparound_, joints_))
    return false;

  default_tolerances_ = getSegmentTolerances<Scalar>(ros::NodeHandle(controller_nh_, "constraints"), joint_names_);

  if (!hw_iface_adapter_.init(joints_, controller_nh_))
  {
    ROS_ERROR_STREAM_NAMED(name_, "Could not initialize the command adapter of '"
                                      << hardware_interface::internal::demangledTypeName<HardwareInterface>() << "'.");
    return false;
  }

  controller_nh_.param("stop_trajectory_duration", stop_trajectory_duration_, 0.0);
  controller_nh_.param("allow_partial_joints_goal", allow_partial_joints_goal_, false);
  double state_publish_rate = 50.0, action_monitor_rate = 20.0;
  if (!internal::publishRates(controller_nh_, name_, state_publish_rate, action_monitor_rate))
    return false;
  state_publish_period_ = 1.0 / state_publish_rate;
  action_monitor_period_ = 1.0 / action_monitor_rate;

  current_state_ = State(n_joints);
  desired_state_ = State(n_joints);
  state_error_ = State(n_joints);
  desired_joint_state_ = State(1);
  hold_state_ = State(1);

  state_publisher_.reset(
      new realtime_tools::RealtimePublisher<control_msgs::JointTrajectoryControllerState>(controller_nh_, "state", 1));
  state_publisher_->lock();
  internal::resetStateMsg(state_publisher_->msg_, joint_names_);
  state_publisher_->unlock();
  feedback_.joint_names = joint_names_;
  feedback_.desired = state_publisher_->msg_.desired;
  feedback_.actual = state_publisher_->msg_.actual;
  feedback_.error = state_publisher_->msg_.error;

  trajectory_command_sub_ =
      controller_nh_.subscribe("command", 1, &JointTrajectoryController::trajectoryCommandCB, this);
  action_server_.reset(new ActionServer(
      controller_nh_, "follow_joint_trajectory", [this](GoalHandle gh) { goalCB(gh); },
      [this](GoalHandle gh) { cancelCB(gh); }, false));
  action_server_->start();
  query_state_service_ =
      controller_nh_.advertiseService("query_state", &JointTrajectoryController::queryStateService, this);
  goal_handle_timer_ =
      controller_nh_.createTimer(ros::Duration(action_monitor_period_), &JointTrajectoryController::monitorGoals, this);

  std::ostringstream joints_list;
  for (unsigned int i = 0; i < n_joints; ++i)
    joints_list << (i ? ", " : "") << joint_names_[i] << (angle_wraparound_[i] ? " (continuous)" : "");
  ROS_DEBUG_STREAM_NAMED(name_, "Initialized controller '"
                                    << name_ << "' with " << n_joints << " joints: " << joints_list.str()
                                    << "; stop_trajectory_duration " << stop_trajectory_duration_ << " s.");
  return true;
}

template <class SegmentImpl, class HardwareInterface>
typename JointTrajectoryController<SegmentImpl, HardwareInterface>::TrajectoryPtr
JointTrajectoryController<SegmentImpl, HardwareInterface>::currentTrajectory() const
{
  std::lock_guard<std::mutex> lock(trajectory_mutex_);
  return curr_trajectory_;
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::setTrajectory(const TrajectoryPtr& traj)
{
  std::lock_guard<std::mutex> lock(trajectory_mutex_);
  curr_trajectory_ = traj;
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::starting(const ros::Time& time)
{
  last_update_nsec_.store(time.toNSec());
  last_state_publish_time_ = time;
  // Hold the current position.
  std::vector<double> actual(joints_.size());
  for (unsigned int i = 0; i < joints_.size(); ++i)
    actual[i] = joints_[i].getPosition();
  setTrajectory(std::make_shared<const Trajectory>(
      holdTrajectory<Segment>(nullptr, actual, time.toSec(), 0.0, GoalTrackerPtr())));
  hw_iface_adapter_.starting(time);
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::stopping(const ros::Time& time)
{
  hw_iface_adapter_.stopping(time);
  // The goal is reported from the (non-realtime) monitor; mark it for preemption there.
  std::unique_lock<std::mutex> lock(goal_mutex_, std::try_to_lock);
  if (lock.owns_lock() && active_goal_ && active_goal_->isActive())
    active_goal_->requestAborted(control_msgs::FollowJointTrajectoryResult::INVALID_GOAL,
                                 "Controller stopped while the goal was executing.");
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::update(const ros::Time& time,
                                                                       const ros::Duration& period)
{
  last_update_nsec_.store(time.toNSec());
  TrajectoryPtr traj_ptr = currentTrajectory();
  if (!traj_ptr)
    return;
  const Trajectory& traj = *traj_ptr;
  const unsigned int n_joints = joints_.size();
  const double now = time.toSec();

  GoalTracker* goal_to_check = nullptr;
  for (unsigned int i = 0; i < n_joints; ++i)
  {
    const SegmentsOfJoint<Segment>& joint_traj = traj[i];
    const std::size_t seg_idx = findSegmentIndex<Segment>(joint_traj, now);
    const JointTrajectorySegment<Segment>& segment = joint_traj[seg_idx];
    segment.sample(now, desired_joint_state_);

    current_state_.position[i] = joints_[i].getPosition();
    current_state_.velocity[i] = joints_[i].getVelocity();
    desired_state_.position[i] = desired_joint_state_.position[0];
    desired_state_.velocity[i] = desired_joint_state_.velocity[0];
    desired_state_.acceleration[i] = desired_joint_state_.acceleration[0];
    state_error_.position[i] =
        angle_wraparound_[i] ? angles::shortest_angular_distance(current_state_.position[i], desired_state_.position[i])
                             : desired_state_.position[i] - current_state_.position[i];
    state_error_.velocity[i] = desired_state_.velocity[i] - current_state_.velocity[i];
    state_error_.acceleration[i] = 0.0;

    // Tolerances of the goal this segment belongs to.
    GoalTracker* goal = dynamic_cast<GoalTracker*>(segment.getGoalHandle().get());
    if (!goal || !goal->isActive())
      continue;
    goal_to_check = goal;
    const SegmentTolerancesPerJoint<Scalar>& tols = segment.getTolerances();
    if (now < segment.endTime())
    {
      if (!checkStateToleranceAt(state_error_, tols.state_tolerance, i))
        goal->requestAborted(control_msgs::FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED,
                             "Path tolerance violated.");
    }
    else if (seg_idx + 1 == joint_traj.size())
    {
      if (checkStateToleranceAt(state_error_, tols.goal_state_tolerance, i))
        goal->successful()[i] = 1;
      else if (!goal->successful()[i] && now > segment.endTime() + tols.goal_time_tolerance)
        goal->requestAborted(control_msgs::FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED,
                             "Goal tolerance violated.");
    }
  }
  if (goal_to_check && goal_to_check->isActive())
    internal::succeedIfDone(*goal_to_check, n_joints);

  hw_iface_adapter_.updateCommand(time, period, desired_state_, state_error_);

  // Feedback for the action monitor (skipped if it is being read right now).
  {
    std::unique_lock<std::mutex> lock(feedback_mutex_, std::try_to_lock);
    if (lock.owns_lock())
    {
      internal::fillStateMsg(feedback_, time, desired_state_, current_state_, state_error_);
      feedback_valid_ = true;
    }
  }

  // State topic, throttled by the update's time.
  if (!(time < last_state_publish_time_ + ros::Duration(state_publish_period_)) || time < last_state_publish_time_)
  {
    if (state_publisher_ && state_publisher_->trylock())
    {
      last_state_publish_time_ += ros::Duration(state_publish_period_);
      if (time - last_state_publish_time_ > ros::Duration(state_publish_period_) || time < last_state_publish_time_)
        last_state_publish_time_ = time;  // fell behind (or time jumped back): restart the schedule
      internal::fillStateMsg(state_publisher_->msg_, time, desired_state_, current_state_, state_error_);
      state_publisher_->unlockAndPublish();
    }
  }
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::setHoldPosition(const ros::Time& time,
                                                                                const GoalTrackerPtr& goal)
{
  std::vector<double> actual(joints_.size());
  for (unsigned int i = 0; i < joints_.size(); ++i)
    actual[i] = joints_[i].getPosition();
  TrajectoryPtr curr = currentTrajectory();
  Trajectory hold = holdTrajectory<Segment>(curr.get(), actual, time.toSec(), stop_trajectory_duration_, goal);
  if (goal)
  {
    for (unsigned int i = 0; i < hold.size(); ++i)
    {
      SegmentTolerancesPerJoint<Scalar> tols;
      tols.state_tolerance = default_tolerances_.state_tolerance[i];
      tols.goal_state_tolerance = default_tolerances_.goal_state_tolerance[i];
      tols.goal_time_tolerance = default_tolerances_.goal_time_tolerance;
      hold[i].back().setTolerances(tols);
    }
  }
  setTrajectory(std::make_shared<const Trajectory>(std::move(hold)));
}

template <class SegmentImpl, class HardwareInterface>
bool JointTrajectoryController<SegmentImpl, HardwareInterface>::updateTrajectoryCommand(
    const trajectory_msgs::JointTrajectory& msg, const GoalTrackerPtr& goal,
    const SegmentTolerances<Scalar>& tolerances, TrajectoryError& error)
{
  if (!this->isRunning())
  {
    error.error_code = control_msgs::FollowJointTrajectoryResult::INVALID_GOAL;
    error.error_string = "Can't accept new commands. Controller is not running.";
    return false;
  }
  const ros::Time now = lastUpdateTime();
  if (msg.points.empty())
  {
    setHoldPosition(now, goal);
    ROS_DEBUG_NAMED(name_, "Empty trajectory command, stopping.");
    return true;
  }
  TrajectoryPtr curr = currentTrajectory();
  UpdateJointTrajectoryOptions<Segment> options;
  options.current_trajectory = curr.get();
  options.joint_names = &joint_names_;
  options.angle_wraparound = &angle_wraparound_;
  options.goal = goal;
  options.tolerances = &tolerances;
  options.allow_partial_joints_goal = allow_partial_joints_goal_;
  Trajectory traj = updateJointTrajectory<Segment>(msg, now, options, error);
  if (traj.empty())
    return false;
  setTrajectory(std::make_shared<const Trajectory>(std::move(traj)));
  return true;
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::trajectoryCommandCB(
    const trajectory_msgs::JointTrajectoryConstPtr& msg)
{
  if (!this->isRunning())
  {
    ROS_ERROR_NAMED(name_, "Can't accept new commands. Controller is not running.");
    return;
  }
  TrajectoryError error;
  if (!msg->points.empty())
  {
    // The topic accepts exactly the controller's joints unless partial goals are allowed.
    mapJoints(msg->joint_names, joint_names_, allow_partial_joints_goal_, error);
    if (error.error_code != 0)
    {
      ROS_ERROR_STREAM_NAMED(name_, "Rejected trajectory on topic 'command': " << error.error_string);
      return;
    }
  }
  if (updateTrajectoryCommand(*msg, GoalTrackerPtr(), default_tolerances_, error))
  {
    preemptActiveGoal();
  }
  else
  {
    if (error.error_code == control_msgs::FollowJointTrajectoryResult::INVALID_JOINTS ||
        error.error_string.find("Dropping all") != 0)
      ROS_ERROR_STREAM_NAMED(name_, "Rejected trajectory on topic 'command': " << error.error_string);
    else
      ROS_WARN_STREAM_NAMED(name_, error.error_string);
  }
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::preemptActiveGoal()
{
  // actionlib calls are made without goal_mutex_ held: actionlib may call us with its own lock held.
  GoalTrackerPtr goal;
  {
    std::lock_guard<std::mutex> lock(goal_mutex_);
    goal.swap(active_goal_);
  }
  if (goal)
    goal->finish();
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::goalCB(GoalHandle gh)
{
  ROS_DEBUG_STREAM_NAMED(name_, "Received new action goal");
  control_msgs::FollowJointTrajectoryResult result;
  const auto goal = gh.getGoal();
  TrajectoryError error;

  if (!this->isRunning())
  {
    result.error_code = control_msgs::FollowJointTrajectoryResult::INVALID_GOAL;
    result.error_string = "Can't accept new action goals. Controller is not running.";
    ROS_ERROR_STREAM_NAMED(name_, result.error_string);
    gh.setRejected(result, result.error_string);
    return;
  }

  const std::vector<unsigned int> mapping =
      mapJoints(goal->trajectory.joint_names, joint_names_, allow_partial_joints_goal_, error);
  if (mapping.empty())
  {
    result.error_code = error.error_code;
    result.error_string = error.error_string;
    ROS_ERROR_STREAM_NAMED(name_, result.error_string);
    gh.setRejected(result, result.error_string);
    return;
  }

  std::vector<bool> covered(joint_names_.size(), false);
  for (unsigned int j : mapping)
    covered[j] = true;
  if (goal->trajectory.points.empty())
    covered.assign(joint_names_.size(), true);  // an empty goal stops every joint
  GoalTrackerPtr tracker(new GoalTracker(gh, covered));
  SegmentTolerances<Scalar> tolerances = default_tolerances_;
  updateSegmentTolerances<Scalar>(*goal, joint_names_, tolerances);

  if (updateTrajectoryCommand(goal->trajectory, tracker, tolerances, error))
  {
    preemptActiveGoal();
    gh.setAccepted();
    // Only now may the monitor report it (a goal can finish before it is accepted otherwise).
    std::lock_guard<std::mutex> lock(goal_mutex_);
    active_goal_ = tracker;
  }
  else
  {
    result.error_code = error.error_code;
    result.error_string = error.error_string;
    ROS_ERROR_STREAM_NAMED(name_, "Rejected goal: " << result.error_string);
    gh.setRejected(result, result.error_string);
  }
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::cancelCB(GoalHandle gh)
{
  GoalTrackerPtr goal;
  {
    std::lock_guard<std::mutex> lock(goal_mutex_);
    goal = active_goal_;
  }
  if (!goal || !(goal->goalHandle() == gh))
    return;
  {
    std::lock_guard<std::mutex> lock(goal_mutex_);
    if (active_goal_ != goal)
      return;  // replaced meanwhile
    active_goal_.reset();
  }
  // Stop where we are, then report the cancellation.
  setHoldPosition(lastUpdateTime());
  goal->finish();
  ROS_DEBUG_NAMED(name_, "Canceling active action goal because cancel callback received from actionlib.");
}

template <class SegmentImpl, class HardwareInterface>
void JointTrajectoryController<SegmentImpl, HardwareInterface>::monitorGoals(const ros::TimerEvent&)
{
  GoalTrackerPtr goal;
  {
    std::lock_guard<std::mutex> lock(goal_mutex_);
    goal = active_goal_;
  }
  if (!goal)
    return;
  if (goal->reportOutcome())
  {
    std::lock_guard<std::mutex> lock(goal_mutex_);
    if (active_goal_ == goal)
      active_goal_.reset();
    return;
  }
  control_msgs::FollowJointTrajectoryFeedback feedback;
  {
    std::lock_guard<std::mutex> fb_lock(feedback_mutex_);
    if (!feedback_valid_)
      return;
    feedback = feedback_;
  }
  goal->goalHandle().publishFeedback(feedback);
}

template <class SegmentImpl, class HardwareInterface>
bool JointTrajectoryController<SegmentImpl, HardwareInterface>::queryStateService(
    control_msgs::QueryTrajectoryState::Request& req, control_msgs::QueryTrajectoryState::Response& resp)
{
  if (!this->isRunning())
  {
    ROS_ERROR_NAMED(name_, "Can't sample trajectory. Controller is not running.");
    return false;
  }
  TrajectoryPtr traj = currentTrajectory();
  if (!traj)
    return false;
  const unsigned int n_joints = joint_names_.size();
  resp.name = joint_names_;
  resp.position.resize(n_joints);
  resp.velocity.resize(n_joints);
  resp.acceleration.resize(n_joints);
  State state;
  for (unsigned int i = 0; i < n_joints; ++i)
  {
    sampleJointTrajectory<Segment>((*traj)[i], req.time.toSec(), state);
    resp.position[i] = state.position[0];
    resp.velocity[i] = state.velocity[0];
    resp.acceleration[i] = state.acceleration[0];
  }
  return true;
}

}  // namespace joint_trajectory_controller
