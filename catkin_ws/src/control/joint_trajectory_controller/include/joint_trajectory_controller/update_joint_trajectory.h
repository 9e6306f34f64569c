// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
// The controller's own trajectory building (updateJointTrajectory, holdTrajectory): the
// trajectory to follow from a trajectory_msgs/JointTrajectory and the one being followed, with
// errors as FollowJointTrajectoryResult codes; plain functions without ROS communication. The
// original's initJointTrajectory is in init_joint_trajectory.h.
#pragma once

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include <control_msgs/FollowJointTrajectoryResult.h>
#include <ros/time.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <joint_trajectory_controller/joint_trajectory_msg_utils.h>
#include <joint_trajectory_controller/joint_trajectory_segment.h>
#include <joint_trajectory_controller/tolerances.h>

namespace joint_trajectory_controller
{
/// One segment list per controller joint.
template <class Segment>
using SegmentsOfJoint = std::vector<JointTrajectorySegment<Segment>>;
template <class Segment>
using SegmentsPerJoint = std::vector<SegmentsOfJoint<Segment>>;

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
inline std::size_t findSegmentIndex(const SegmentsOfJoint<Segment>& traj, double time)
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

/// Sample a joint's trajectory at \p time (see findSegmentIndex).
template <class Segment>
inline void sampleJointTrajectory(const SegmentsOfJoint<Segment>& traj, double time, typename Segment::State& state)
{
  traj[findSegmentIndex<Segment>(traj, time)].sample(time, state);
}

/**
 * \brief Map the message's joints onto the controller's: result[k] is the controller index of the
 * message's k-th joint. Fills \p error (INVALID_JOINTS) and returns an empty vector on unknown or
 * repeated names, or on a partial set of joints when \p allow_partial_joints_goal is false.
 */
inline std::vector<unsigned int> mapJoints(const std::vector<std::string>& msg_joints,
                                           const std::vector<std::string>& joint_names, bool allow_partial_joints_goal,
                                           TrajectoryError& error)
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
        (!p.accelerations.empty() && p.accelerations.size() != n) || (!p.accelerations.empty() && p.velocities.empty()))
    {
      std::ostringstream os;
      os << "Invalid trajectory point " << k << ": it must have " << n << " positions, and either no or " << n
         << " velocities and accelerations (accelerations only with velocities).";
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

/// Options of updateJointTrajectory (the controller's variant of initJointTrajectory).
template <class Segment>
struct UpdateJointTrajectoryOptions
{
  typedef typename Segment::Scalar Scalar;
  const SegmentsPerJoint<Segment>* current_trajectory = nullptr;  ///< the trajectory being followed (required)
  const std::vector<std::string>* joint_names = nullptr;          ///< the controller's joints (required)
  const std::vector<bool>* angle_wraparound = nullptr;            ///< per joint: continuous (optional)
  GoalTrackerPtr goal;                                            ///< goal the new segments belong to (optional)
  const SegmentTolerances<Scalar>* tolerances = nullptr;          ///< tolerances of the new segments (optional)
  bool allow_partial_joints_goal = false;
};

/// updateJointTrajectory for one joint: the message's \p k-th joint, controller joint \p j, whose
/// trajectory \p curr runs until \p last_curr_time; \p first is the message's first future point.
template <class Segment>
SegmentsOfJoint<Segment> updatedJointSegments(const trajectory_msgs::JointTrajectory& msg, unsigned int k,
                                              unsigned int j, std::size_t first, const ros::Time& msg_start, double now,
                                              double last_curr_time, const SegmentsOfJoint<Segment>& curr,
                                              const UpdateJointTrajectoryOptions<Segment>& options)
{
  typedef typename Segment::State State;
  SegmentsOfJoint<Segment> out;

  State last_curr_state;
  sampleJointTrajectory<Segment>(curr, last_curr_time, last_curr_state);
  const bool wrap = options.angle_wraparound && (*options.angle_wraparound)[j];
  const double offset = wraparoundJointOffset(last_curr_state.position[0], msg.points[first].positions[k], wrap);

  SegmentTolerancesPerJoint<typename Segment::Scalar> tols;
  if (options.tolerances)
  {
    tols.state_tolerance = options.tolerances->state_tolerance[j];
    tols.goal_state_tolerance = options.tolerances->goal_state_tolerance[j];
    tols.goal_time_tolerance = options.tolerances->goal_time_tolerance;
  }

  // Segments of the current trajectory still executed until the new one starts.
  const std::size_t first_seg = findSegmentIndex<Segment>(curr, now);
  const std::size_t last_seg = findSegmentIndex<Segment>(curr, last_curr_time);
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
  return out;
}

/**
 * \brief The controller's variant of initJointTrajectory: the message is validated first and
 * refused with a FollowJointTrajectoryResult error code (no exception), the goal's tolerances
 * come resolved. The trajectory to follow after \p msg arrives at \p time: the current trajectory up to
 * the message's start time (header.stamp, or \p time if zero), a segment bridging the current
 * desired state to the message's first point that is still in the future, then the message's
 * points. Joints the message leaves out keep their current trajectory. Points already in the past
 * are dropped; if none remains the result is empty and \p error says why (INVALID_GOAL).
 */
template <class Segment>
SegmentsPerJoint<Segment> updateJointTrajectory(const trajectory_msgs::JointTrajectory& msg, const ros::Time& time,
                                                const UpdateJointTrajectoryOptions<Segment>& options,
                                                TrajectoryError& error)
{
  const std::vector<std::string>& joint_names = *options.joint_names;
  const SegmentsPerJoint<Segment>& current = *options.current_trajectory;
  const std::size_t n_joints = joint_names.size();

  SegmentsPerJoint<Segment> result;
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
    result[mapping[k]] = updatedJointSegments<Segment>(msg, k, mapping[k], first, msg_start, now, last_curr_time,
                                                       current[mapping[k]], options);
  return result;
}

/**
 * \brief A trajectory that stops every joint at \p time: with \p stop_duration > 0, from the
 * desired state of \p current (position, velocity) to zero velocity over \p stop_duration; with
 * \p stop_duration <= 0, at \p actual_positions at once.
 */
template <class Segment>
SegmentsPerJoint<Segment> holdTrajectory(const SegmentsPerJoint<Segment>* current,
                                         const std::vector<double>& actual_positions, double time, double stop_duration,
                                         const GoalTrackerPtr& goal = GoalTrackerPtr())
{
  typedef typename Segment::State State;
  const std::size_t n_joints = actual_positions.size();
  SegmentsPerJoint<Segment> result(n_joints);
  for (std::size_t j = 0; j < n_joints; ++j)
  {
    State start(1), end(1);
    double end_time = time;
    if (stop_duration > 0.0 && current && current->size() == n_joints && !(*current)[j].empty())
    {
      State desired;
      sampleJointTrajectory<Segment>((*current)[j], time, desired);
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
