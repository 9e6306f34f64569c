// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
// Building the trajectory to follow from a trajectory_msgs/JointTrajectory and the one being
// followed; plain functions without ROS communication, unit-tested on their own.
#pragma once

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <angles/angles.h>
#include <boost/shared_ptr.hpp>
#include <realtime_tools/realtime_server_goal_handle.h>
#include <ros/console.h>
#include <ros/time.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <joint_trajectory_controller/joint_trajectory_msg_utils.h>
#include <joint_trajectory_controller/joint_trajectory_segment.h>
#include <joint_trajectory_controller/tolerances.h>
#include <trajectory_interface/trajectory_interface.h>

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
  typedef typename Segment::State State;
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
  {
    const unsigned int j = mapping[k];
    const SegmentsOfJoint<Segment>& curr = current[j];
    SegmentsOfJoint<Segment>& out = result[j];
    out.clear();

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
  }
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

// ---------------------------------------------------------------------------------------------
// The original's API (ros_controllers 0.21): initJointTrajectory<Trajectory> with a per-joint
// Trajectory = std::vector<std::vector<JointTrajectorySegment<...>>>.
// ---------------------------------------------------------------------------------------------

namespace internal
{
/**
 * \brief For each element of \p t1, its index in \p t2 (\p t1 must be a subset of \p t2); empty if
 * \p t1 is larger than \p t2 or has an element \p t2 lacks. {C, B} in {A, B, C, D} gives {2, 1}.
 */
template <class T>
inline std::vector<unsigned int> mapping(const T& t1, const T& t2)
{
  std::vector<unsigned int> result;
  if (t1.size() > t2.size())
    return result;
  result.reserve(t1.size());
  for (const auto& item : t1)
  {
    const auto found = std::find(t2.begin(), t2.end(), item);
    if (found == t2.end())
      return std::vector<unsigned int>();
    result.push_back(static_cast<unsigned int>(std::distance(t2.begin(), found)));
  }
  return result;
}

/**
 * \brief For each element of \p t1, its index in \p t2, when both hold the same elements in any
 * order; empty if their sizes differ or an element is missing. {A, B, C, D} against
 * {B, D, A, C} gives {2, 0, 3, 1}.
 */
template <class T>
inline std::vector<unsigned int> permutation(const T& t1, const T& t2)
{
  if (t1.size() != t2.size())
    return std::vector<unsigned int>();
  return mapping(t1, t2);
}
}  // namespace internal

/**
 * \brief Options of initJointTrajectory (all optional; pointers are not owned).
 * \tparam Trajectory Per-joint container of per-segment containers, e.g.
 * std::vector<std::vector<JointTrajectorySegment<QuinticSplineSegment<double>>>>.
 */
template <class Trajectory>
struct InitJointTrajectoryOptions
{
  typedef realtime_tools::RealtimeServerGoalHandle<control_msgs::FollowJointTrajectoryAction> RealtimeGoalHandle;
  typedef boost::shared_ptr<RealtimeGoalHandle> RealtimeGoalHandlePtr;
  typedef typename Trajectory::value_type TrajectoryPerJoint;
  typedef typename TrajectoryPerJoint::value_type Segment;
  typedef typename Segment::Scalar Scalar;

  InitJointTrajectoryOptions()
    : current_trajectory(nullptr)
    , joint_names(nullptr)
    , angle_wraparound(nullptr)
    , rt_goal_handle()
    , default_tolerances(nullptr)
    , other_time_base(nullptr)
    , allow_partial_joints_goal(false)
    , error_string(nullptr)
  {
  }

  /// The trajectory being followed (one entry per joint of joint_names), kept up to the new start.
  Trajectory* current_trajectory;
  /// The expected joints, in the result's order (default: the message's joints and order).
  std::vector<std::string>* joint_names;
  /// Per expected joint: continuous (used only together with current_trajectory).
  std::vector<bool>* angle_wraparound;
  /// Goal the new segments belong to; its tolerances override default_tolerances.
  RealtimeGoalHandlePtr rt_goal_handle;
  /// Tolerances of the new segments (applied when rt_goal_handle is given).
  SegmentTolerances<Scalar>* default_tolerances;
  /// \p time expressed in the time base of current_trajectory and of the result.
  ros::Time* other_time_base;
  /// Accept a message that names only some of joint_names.
  bool allow_partial_joints_goal;
  /// Receives why the result is empty.
  std::string* error_string;

  void setErrorString(const std::string& msg) const
  {
    if (error_string)
      *error_string = msg;
  }
};

/// True if a joint's trajectory has segments.
template <class Trajectory>
bool isNotEmpty(typename Trajectory::value_type traj_per_joint)
{
  return !traj_per_joint.empty();
}

namespace internal
{
/// The \p msg_index-th joint of \p point as a one-joint point.
inline trajectory_msgs::JointTrajectoryPoint jointPoint(const trajectory_msgs::JointTrajectoryPoint& point,
                                                        unsigned int msg_index)
{
  trajectory_msgs::JointTrajectoryPoint out;
  if (!point.positions.empty())
    out.positions.assign(1, point.positions[msg_index]);
  if (!point.velocities.empty())
    out.velocities.assign(1, point.velocities[msg_index]);
  if (!point.accelerations.empty())
    out.accelerations.assign(1, point.accelerations[msg_index]);
  out.time_from_start = point.time_from_start;
  return out;
}

/// Report an empty result: log \p what at ERROR (or DEBUG) and hand it to options.error_string.
template <class Options>
inline void initFailed(const Options& options, const std::string& what, bool debug_only = false)
{
  if (debug_only)
    ROS_DEBUG_STREAM(what);
  else
    ROS_ERROR_STREAM(what);
  options.setErrorString(what);
}
}  // namespace internal

/**
 * \brief The trajectory (one segment list per joint) described by \p msg from \p time on,
 * combined with options.current_trajectory if given.
 *
 * Points of \p msg reached at or before \p time are dropped (the message starts at its
 * header.stamp, or at \p time if that is zero). Without a current trajectory each joint gets the
 * segments between the remaining points (none if a single point remains). With one, each joint
 * the message names keeps the current segments from the one active at \p time to the one active
 * when the message starts, then gets a segment bridging the current state at that moment to the
 * first remaining point (wrapped to the nearest turn for continuous joints), then the message's
 * segments; joints the message leaves out (allow_partial_joints_goal) keep their trajectory, and
 * every current segment from \p time on is attached to options.rt_goal_handle. The new segments
 * carry options.rt_goal_handle and, when it is given, the default tolerances updated by its
 * goal. The result is empty (and options.error_string says why) for an empty message, times not
 * strictly increasing, joints that are not the expected ones, an angle_wraparound of the wrong
 * size, or every point in the past.
 *
 * \throw std::invalid_argument If a point's positions, velocities and accelerations disagree in size.
 */
template <class Trajectory>
Trajectory initJointTrajectory(
    const trajectory_msgs::JointTrajectory& msg, const ros::Time& time,
    const InitJointTrajectoryOptions<Trajectory>& options = InitJointTrajectoryOptions<Trajectory>())
{
  typedef typename Trajectory::value_type TrajectoryPerJoint;
  typedef typename TrajectoryPerJoint::value_type Segment;
  typedef typename Segment::Scalar Scalar;
  typedef std::vector<trajectory_msgs::JointTrajectoryPoint>::const_iterator PointIter;

  const ros::Time msg_start_time = internal::startTime(msg, time);

  if (msg.points.empty())
  {
    internal::initFailed(options, "Trajectory message contains empty trajectory. Nothing to convert.", true);
    return Trajectory();
  }
  if (!isTimeStrictlyIncreasing(msg))
  {
    internal::initFailed(options, "Trajectory message contains waypoints that are not strictly increasing in time.");
    return Trajectory();
  }

  const bool has_current_trajectory = options.current_trajectory && !options.current_trajectory->empty();
  const bool has_joint_names = options.joint_names && !options.joint_names->empty();
  const bool has_angle_wraparound = options.angle_wraparound && !options.angle_wraparound->empty();
  const bool has_rt_goal_handle = options.rt_goal_handle != nullptr;

  if (!has_current_trajectory && has_angle_wraparound)
    ROS_WARN("Vector specifying whether joints wrap around will not be used because no current trajectory was given.");

  // The same instants in the result's time base (o_ prefix).
  ros::Time o_time = time;
  ros::Time o_msg_start_time = msg_start_time;
  if (options.other_time_base)
  {
    o_time = *options.other_time_base;
    o_msg_start_time = o_time + (msg_start_time - time);
  }

  const std::vector<std::string> joint_names = has_joint_names ? *options.joint_names : msg.joint_names;

  if (has_angle_wraparound && options.angle_wraparound->size() != joint_names.size())
  {
    internal::initFailed(options,
                         "Cannot create trajectory from message. "
                         "Vector specifying whether joints wrap around has an invalid size.");
    return Trajectory();
  }
  if (!options.allow_partial_joints_goal && msg.joint_names.size() != joint_names.size())
  {
    internal::initFailed(options, "Cannot create trajectory from message. It does not contain the expected joints.");
    return Trajectory();
  }
  const std::vector<unsigned int> mapping_vector = internal::mapping(msg.joint_names, joint_names);
  if (mapping_vector.empty())
  {
    internal::initFailed(options, "Cannot create trajectory from message. It does not contain the expected joints.");
    return Trajectory();
  }
  if (has_current_trajectory && options.current_trajectory->size() != joint_names.size())
  {
    internal::initFailed(options,
                         "Cannot create trajectory from message. "
                         "The current trajectory does not have one entry per expected joint.");
    return Trajectory();
  }

  SegmentTolerances<Scalar> tolerances =
      options.default_tolerances ? *options.default_tolerances : SegmentTolerances<Scalar>(joint_names.size());
  if (has_rt_goal_handle && options.rt_goal_handle->gh_.getGoal())
    updateSegmentTolerances<Scalar>(*options.rt_goal_handle->gh_.getGoal(), joint_names, tolerances);

  // First point reached after 'time' (NOTE: 'time', not 'o_time').
  PointIter first_point = findPoint(msg, time);
  if (first_point == msg.points.end())
  {
    first_point = msg.points.begin();
  }
  else
  {
    ++first_point;
    if (first_point == msg.points.end())
    {
      const ros::Duration last_point_dur = time - (msg_start_time + msg.points.back().time_from_start);
      std::ostringstream os;
      os << "Dropping all " << msg.points.size() << " trajectory point(s), as they occur before the current time.\n"
         << "Last point is " << last_point_dur.toSec() << "s in the past.";
      ROS_WARN_STREAM(os.str());
      options.setErrorString(os.str());
      return Trajectory();
    }
    if (!(msg.points.front().time_from_start.isZero() && msg.header.stamp.isZero() &&
          first_point - msg.points.begin() == 1))
    {
      ROS_WARN_STREAM("Dropping first " << (first_point - msg.points.begin()) << " trajectory point(s) out of "
                                        << msg.points.size() << ", as they occur before the current time.");
    }
  }

  Trajectory result;
  if (has_current_trajectory)
  {
    result = *options.current_trajectory;
    // What remains of the current trajectory now belongs to the new goal.
    for (TrajectoryPerJoint& joint_traj : result)
    {
      auto active = trajectory_interface::findSegment(joint_traj, static_cast<typename Segment::Time>(o_time.toSec()));
      for (; active != joint_traj.end(); ++active)
        active->setGoalHandle(options.rt_goal_handle);
    }
  }
  else
  {
    result.resize(joint_names.size());
  }

  for (unsigned int msg_joint = 0; msg_joint < mapping_vector.size(); ++msg_joint)
  {
    const unsigned int joint_id = mapping_vector[msg_joint];
    TrajectoryPerJoint joint_result;
    std::vector<Scalar> position_offset(1, Scalar(0));

    SegmentTolerancesPerJoint<Scalar> joint_tolerances;
    joint_tolerances.state_tolerance = tolerances.state_tolerance[joint_id];
    joint_tolerances.goal_state_tolerance = tolerances.goal_state_tolerance[joint_id];
    joint_tolerances.goal_time_tolerance = tolerances.goal_time_tolerance;

    PointIter it = first_point;
    if (!isValid(*it, it->positions.size()) || it->positions.size() != msg.joint_names.size())
      throw std::invalid_argument("Size mismatch in trajectory point position, velocity or acceleration data.");

    if (has_current_trajectory)
    {
      const TrajectoryPerJoint& curr = (*options.current_trajectory)[joint_id];
      const typename Segment::Time last_curr_time =
          std::max(o_msg_start_time.toSec(), o_time.toSec());  // the current trajectory runs until then
      typename Segment::State last_curr_state;
      trajectory_interface::sample(curr, last_curr_time, last_curr_state);

      const trajectory_msgs::JointTrajectoryPoint first_joint_point = internal::jointPoint(*it, msg_joint);
      const typename Segment::Time first_new_time = o_msg_start_time.toSec() + it->time_from_start.toSec();
      typename Segment::State first_new_state(first_joint_point);
      if (has_angle_wraparound && !last_curr_state.position.empty())
      {
        position_offset[0] = wraparoundJointOffset<Scalar>(last_curr_state.position[0], first_new_state.position[0],
                                                           (*options.angle_wraparound)[joint_id]);
        first_new_state = typename Segment::State(first_joint_point, position_offset);
      }

      const auto first_seg =
          trajectory_interface::findSegment(curr, static_cast<typename Segment::Time>(o_time.toSec()));
      const auto last_seg = trajectory_interface::findSegment(curr, last_curr_time);
      if (first_seg == curr.end() || last_seg == curr.end())
      {
        internal::initFailed(options, "Unexpected error: Could not find segments in current trajectory.");
        return Trajectory();
      }
      joint_result.insert(joint_result.end(), first_seg, std::next(last_seg));

      Segment bridge(last_curr_time, last_curr_state, first_new_time, first_new_state);
      bridge.setGoalHandle(options.rt_goal_handle);
      if (has_rt_goal_handle)
        bridge.setTolerances(joint_tolerances);
      joint_result.push_back(bridge);
    }

    for (; std::distance(it, msg.points.end()) >= 2; ++it)
    {
      const PointIter next = std::next(it);
      if (!isValid(*next, next->positions.size()) || next->positions.size() != msg.joint_names.size())
        throw std::invalid_argument("Size mismatch in trajectory point position, velocity or acceleration data.");
      Segment segment(o_msg_start_time, internal::jointPoint(*it, msg_joint), internal::jointPoint(*next, msg_joint),
                      position_offset);
      segment.setGoalHandle(options.rt_goal_handle);
      if (has_rt_goal_handle)
        segment.setTolerances(joint_tolerances);
      joint_result.push_back(segment);
    }

    ROS_DEBUG_STREAM("Trajectory of joint " << joint_names[joint_id] << " has " << joint_result.size() << " segments.");
    if (!joint_result.empty())
      result[joint_id] = joint_result;
  }

  if (std::find_if(result.begin(), result.end(), isNotEmpty<Trajectory>) == result.end())
    result.clear();
  return result;
}

}  // namespace joint_trajectory_controller
