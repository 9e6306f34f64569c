// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
// Building the trajectory to follow from a trajectory_msgs/JointTrajectory and the one being
// followed; plain functions without ROS communication, unit-tested on their own.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <angles/angles.h>
#include <ros/time.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <joint_trajectory_controller/joint_trajectory_segment.h>
#include <joint_trajectory_controller/tolerances.h>

namespace joint_trajectory_controller
{
/// One segment list per controller joint.
template <class Segment>
using JointTrajectory = std::vector<JointTrajectorySegment<Segment>>;
template <class Segment>
using Trajectory = std::vector<JointTrajectory<Segment>>;

/// Why a trajectory message was refused (values are FollowJointTrajectoryResult error codes).
struct TrajectoryError
{
  int error_code = 0;  ///< 0: accepted
  std::string error_string;
};

/**
 * \brief Index of the segment of \p traj active at \p time: the last one that starts at or before
 * \p time, or the first one if \p time precedes them all. \p traj must not be empty.
 */
template <class Segment>
inline std::size_t findSegment(const JointTrajectory<Segment>& traj, double time)
{
  std::size_t idx = 0;
  for (std::size_t i = 1; i < traj.size(); ++i)
  {
    if (traj[i].startTime() <= time)
      idx = i;
    else
      break;
  }
  return idx;
}

/// Sample a joint's trajectory at \p time (see findSegment).
template <class Segment>
inline void sample(const JointTrajectory<Segment>& traj, double time, typename Segment::State& state)
{
  traj[findSegment<Segment>(traj, time)].sample(time, state);
}

/**
 * \brief Offset to add to a continuous joint's new positions so that moving from \p prev_position
 * to \p next_position takes the shortest way (a half-turn goes the way the raw difference points).
 */
inline double wraparoundJointOffset(double prev_position, double next_position, bool angle_wraparound)
{
  if (!angle_wraparound)
    return 0.0;
  double dist = angles::shortest_angular_distance(prev_position, next_position);
  if (std::abs(std::abs(dist) - M_PI) < 1e-6)
    dist = next_position > prev_position ? std::abs(dist) : -std::abs(dist);
  return prev_position + dist - next_position;
}

/**
 * \brief Map the message's joints onto the controller's: result[k] is the controller index of the
 * message's k-th joint. Fills \p error (INVALID_JOINTS) and returns an empty vector on unknown or
 * repeated names, or on a partial set of joints when \p allow_partial_joints_goal is false.
 */
inline std::vector<unsigned int> mapJoints(const std::vector<std::string>& msg_joints,
                                           const std::vector<std::string>& joint_names,
                                           bool allow_partial_joints_goal, TrajectoryError& error)
{
  std::vector<unsigned int> mapping;
  const int invalid_joints = control_msgs::FollowJointTrajectoryResult::INVALID_JOINTS;
  if (msg_joints.empty() || (!allow_partial_joints_goal && msg_joints.size() != joint_names.size()) ||
      msg_joints.size() > joint_names.size())
  {
    error.error_code = invalid_joints;
    error.error_string = "Joints on incoming goal don't match the controller joints.";
    return mapping;
  }
  std::vector<bool> used(joint_names.size(), false);
  for (const std::string& name : msg_joints)
  {
    std::size_t j = 0;
    while (j < joint_names.size() && joint_names[j] != name)
      ++j;
    if (j == joint_names.size() || used[j])
    {
      error.error_code = invalid_joints;
      error.error_string = "Joints on incoming goal don't match the controller joints.";
      return {};
    }
    used[j] = true;
    mapping.push_back(static_cast<unsigned int>(j));
  }
  return mapping;
}

/// Check the points' sizes and strictly increasing times; fills \p error (INVALID_GOAL).
inline bool isValid(const trajectory_msgs::JointTrajectory& msg, TrajectoryError& error)
{
  const std::size_t n = msg.joint_names.size();
  const int invalid_goal = control_msgs::FollowJointTrajectoryResult::INVALID_GOAL;
  for (std::size_t k = 0; k < msg.points.size(); ++k)
  {
    const trajectory_msgs::JointTrajectoryPoint& p = msg.points[k];
    if (p.positions.size() != n || (!p.velocities.empty() && p.velocities.size() != n) ||
        (!p.accelerations.empty() && p.accelerations.size() != n) ||
        (!p.accelerations.empty() && p.velocities.empty()))
    {
      std::ostringstream os;
      os << "Invalid trajectory point " << k << ": it must have " << n
         << " positions, and either no or " << n << " velocities and accelerations (accelerations only with velocities).";
      error.error_code = invalid_goal;
      error.error_string = os.str();
      return false;
    }
    if (k > 0 && !(p.time_from_start > msg.points[k - 1].time_from_start))
    {
      std::ostringstream os;
      os << "Trajectory message contains waypoints that are not strictly increasing in time (point " << k << ").";
      error.error_code = invalid_goal;
      error.error_string = os.str();
      return false;
    }
  }
  return true;
}

/// The state of the message's \p msg_index-th joint at a point, shifted by \p offset.
template <class State>
inline State pointState(const trajectory_msgs::JointTrajectoryPoint& p, unsigned int msg_index, double offset)
{
  State s;
  s.position.assign(1, p.positions[msg_index] + offset);
  if (!p.velocities.empty())
    s.velocity.assign(1, p.velocities[msg_index]);
  if (!p.accelerations.empty())
    s.acceleration.assign(1, p.accelerations[msg_index]);
  return s;
}

/// Options of initJointTrajectory.
template <class Segment>
struct InitJointTrajectoryOptions
{
  typedef typename Segment::Scalar Scalar;
  const Trajectory<Segment>* current_trajectory = nullptr;  ///< the trajectory being followed (required)
  const std::vector<std::string>* joint_names = nullptr;    ///< the controller's joints (required)
  const std::vector<bool>* angle_wraparound = nullptr;      ///< per joint: continuous (optional)
  GoalTrackerPtr goal;                                      ///< goal the new segments belong to (optional)
  const SegmentTolerances<Scalar>* tolerances = nullptr;    ///< tolerances of the new segments (optional)
  bool allow_partial_joints_goal = false;
};

/**
 * \brief The trajectory to follow after \p msg arrives at \p time: the current trajectory up to
 * the message's start time (header.stamp, or \p time if zero), a segment bridging the current
 * desired state to the message's first point that is still in the future, then the message's
 * points. Joints the message leaves out keep their current trajectory. Points already in the past
 * are dropped; if none remains the result is empty and \p error says why (INVALID_GOAL).
 */
template <class Segment>
Trajectory<Segment> initJointTrajectory(const trajectory_msgs::JointTrajectory& msg, const ros::Time& time,
                                        const InitJointTrajectoryOptions<Segment>& options, TrajectoryError& error)
{
  typedef typename Segment::State State;
  const std::vector<std::string>& joint_names = *options.joint_names;
  const Trajectory<Segment>& current = *options.current_trajectory;
  const std::size_t n_joints = joint_names.size();

  Trajectory<Segment> result;
  const std::vector<unsigned int> mapping =
      mapJoints(msg.joint_names, joint_names, options.allow_partial_joints_goal, error);
  if (mapping.empty() || !isValid(msg, error))
    return result;
  if (current.size() != n_joints)
  {
    error.error_code = control_msgs::FollowJointTrajectoryResult::INVALID_GOAL;
    error.error_string = "Cannot update the trajectory: the controller has no current trajectory (not started).";
    return result;
  }

  const ros::Time msg_start = msg.header.stamp.isZero() ? time : msg.header.stamp;
  // First point occurring after the current time.
  std::size_t first = 0;
  while (first < msg.points.size() && !(msg_start + msg.points[first].time_from_start > time))
    ++first;
  if (first == msg.points.size())
  {
    std::ostringstream os;
    os << "Dropping all " << msg.points.size() << " trajectory point(s), as they occur before the current time.";
    error.error_code = control_msgs::FollowJointTrajectoryResult::INVALID_GOAL;
    error.error_string = os.str();
    return result;
  }

  const double now = time.toSec();
  const double last_curr_time = std::max(msg_start.toSec(), now);
  result = current;  // joints the message does not move keep their trajectory
  for (unsigned int k = 0; k < mapping.size(); ++k)
  {
    const unsigned int j = mapping[k];
    const JointTrajectory<Segment>& curr = current[j];
    JointTrajectory<Segment>& out = result[j];
    out.clear();

    State last_curr_state;
    sample<Segment>(curr, last_curr_time, last_curr_state);
    const bool wrap = options.angle_wraparound && (*options.angle_wraparound)[j];
    const double offset =
        wraparoundJointOffset(last_curr_state.position[0], msg.points[first].positions[k], wrap);

    SegmentTolerancesPerJoint<typename Segment::Scalar> tols;
    if (options.tolerances)
    {
      tols.state_tolerance = options.tolerances->state_tolerance[j];
      tols.goal_state_tolerance = options.tolerances->goal_state_tolerance[j];
      tols.goal_time_tolerance = options.tolerances->goal_time_tolerance;
    }

    // Segments of the current trajectory still executed until the new one starts.
    const std::size_t first_seg = findSegment<Segment>(curr, now);
    const std::size_t last_seg = findSegment<Segment>(curr, last_curr_time);
    for (std::size_t s = first_seg; s <= last_seg; ++s)
      out.push_back(curr[s]);

    // Bridge from the current desired state to the first new point.
    double prev_time = (msg_start + msg.points[first].time_from_start).toSec();
    State prev_state = pointState<State>(msg.points[first], k, offset);
    out.emplace_back(last_curr_time, last_curr_state, prev_time, prev_state);
    out.back().setGoalHandle(options.goal);
    out.back().setTolerances(tols);

    for (std::size_t p = first + 1; p < msg.points.size(); ++p)
    {
      const double t = (msg_start + msg.points[p].time_from_start).toSec();
      State s = pointState<State>(msg.points[p], k, offset);
      out.emplace_back(prev_time, prev_state, t, s);
      out.back().setGoalHandle(options.goal);
      out.back().setTolerances(tols);
      prev_time = t;
      prev_state = s;
    }
  }
  return result;
}

/**
 * \brief A trajectory that stops every joint at \p time: with \p stop_duration > 0, from the
 * desired state of \p current (position, velocity) to zero velocity over \p stop_duration; with
 * \p stop_duration <= 0, at \p actual_positions at once.
 */
template <class Segment>
Trajectory<Segment> holdTrajectory(const Trajectory<Segment>* current, const std::vector<double>& actual_positions,
                                   double time, double stop_duration, const GoalTrackerPtr& goal = GoalTrackerPtr())
{
  typedef typename Segment::State State;
  const std::size_t n_joints = actual_positions.size();
  Trajectory<Segment> result(n_joints);
  for (std::size_t j = 0; j < n_joints; ++j)
  {
    State start(1), end(1);
    double end_time = time;
    if (stop_duration > 0.0 && current && current->size() == n_joints && !(*current)[j].empty())
    {
      State desired;
      sample<Segment>((*current)[j], time, desired);
      start.position[0] = desired.position[0];
      start.velocity[0] = desired.velocity[0];
      end.position[0] = desired.position[0] + 0.5 * desired.velocity[0] * stop_duration;
      end_time = time + stop_duration;
    }
    else
    {
      start.position[0] = actual_positions[j];
      end.position[0] = actual_positions[j];
    }
    result[j].emplace_back(time, start, end_time, end);
    result[j].back().setGoalHandle(goal);
  }
  return result;
}

}  // namespace joint_trajectory_controller
