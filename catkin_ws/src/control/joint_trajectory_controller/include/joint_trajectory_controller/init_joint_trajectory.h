// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
// The original's initJointTrajectory: the trajectory to follow from a
// trajectory_msgs/JointTrajectory and the one being followed; plain functions without ROS
// communication, unit-tested on their own. The controller's own variant (updateJointTrajectory,
// holdTrajectory) is in update_joint_trajectory.h, included here.
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
#include <joint_trajectory_controller/update_joint_trajectory.h>
#include <trajectory_interface/trajectory_interface.h>

namespace joint_trajectory_controller
{
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

/// The message's joints mapped onto the expected ones (see initJointTrajectory); empty, with the
/// reason reported, when they do not match or the options disagree in size.
template <class Options>
std::vector<unsigned int> checkedMapping(const trajectory_msgs::JointTrajectory& msg,
                                         const std::vector<std::string>& joint_names, const Options& options)
{
  const bool has_current_trajectory = options.current_trajectory && !options.current_trajectory->empty();
  const bool has_angle_wraparound = options.angle_wraparound && !options.angle_wraparound->empty();
  if (has_angle_wraparound && options.angle_wraparound->size() != joint_names.size())
  {
    initFailed(options,
               "Cannot create trajectory from message. "
               "Vector specifying whether joints wrap around has an invalid size.");
    return std::vector<unsigned int>();
  }
  if (!options.allow_partial_joints_goal && msg.joint_names.size() != joint_names.size())
  {
    initFailed(options, "Cannot create trajectory from message. It does not contain the expected joints.");
    return std::vector<unsigned int>();
  }
  const std::vector<unsigned int> mapping_vector = mapping(msg.joint_names, joint_names);
  if (mapping_vector.empty())
  {
    initFailed(options, "Cannot create trajectory from message. It does not contain the expected joints.");
    return mapping_vector;
  }
  if (has_current_trajectory && options.current_trajectory->size() != joint_names.size())
  {
    initFailed(options,
               "Cannot create trajectory from message. "
               "The current trajectory does not have one entry per expected joint.");
    return std::vector<unsigned int>();
  }
  return mapping_vector;
}

/// The message's first point reached after \p time (the first point when \p time precedes them
/// all); msg.points.end(), with a WARN and the error string, when every point is in the past.
template <class Options>
std::vector<trajectory_msgs::JointTrajectoryPoint>::const_iterator firstRemainingPoint(
    const trajectory_msgs::JointTrajectory& msg, const ros::Time& time, const ros::Time& msg_start_time,
    const Options& options)
{
  std::vector<trajectory_msgs::JointTrajectoryPoint>::const_iterator first_point = findPoint(msg, time);
  if (first_point == msg.points.end())
    return msg.points.begin();
  ++first_point;
  if (first_point == msg.points.end())
  {
    const ros::Duration last_point_dur = time - (msg_start_time + msg.points.back().time_from_start);
    std::ostringstream os;
    os << "Dropping all " << msg.points.size() << " trajectory point(s), as they occur before the current time.\n"
       << "Last point is " << last_point_dur.toSec() << "s in the past.";
    ROS_WARN_STREAM(os.str());
    options.setErrorString(os.str());
    return msg.points.end();
  }
  if (!(msg.points.front().time_from_start.isZero() && msg.header.stamp.isZero() &&
        first_point - msg.points.begin() == 1))
  {
    ROS_WARN_STREAM("Dropping first " << (first_point - msg.points.begin()) << " trajectory point(s) out of "
                                      << msg.points.size() << ", as they occur before the current time.");
  }
  return first_point;
}

/// initJointTrajectory for the message's \p msg_joint-th joint (expected joint \p joint_id): the
/// current segments kept and the bridge (with a current trajectory), then the message's
/// segments from \p first_point; false, with the reason reported, on an unexpected error.
/// \throw std::invalid_argument If a point's positions, velocities and accelerations disagree in size.
template <class Trajectory>
bool jointSegmentsFromMessage(const trajectory_msgs::JointTrajectory& msg, unsigned int msg_joint,
                              unsigned int joint_id,
                              std::vector<trajectory_msgs::JointTrajectoryPoint>::const_iterator first_point,
                              const ros::Time& o_time, const ros::Time& o_msg_start_time,
                              const SegmentTolerances<typename Trajectory::value_type::value_type::Scalar>& tolerances,
                              const InitJointTrajectoryOptions<Trajectory>& options,
                              typename Trajectory::value_type& joint_result)
{
  typedef typename Trajectory::value_type TrajectoryPerJoint;
  typedef typename TrajectoryPerJoint::value_type Segment;
  typedef typename Segment::Scalar Scalar;
  typedef std::vector<trajectory_msgs::JointTrajectoryPoint>::const_iterator PointIter;
  const bool has_current_trajectory = options.current_trajectory && !options.current_trajectory->empty();
  const bool has_angle_wraparound = options.angle_wraparound && !options.angle_wraparound->empty();
  const bool has_rt_goal_handle = options.rt_goal_handle != nullptr;

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

    const trajectory_msgs::JointTrajectoryPoint first_joint_point = jointPoint(*it, msg_joint);
    const typename Segment::Time first_new_time = o_msg_start_time.toSec() + it->time_from_start.toSec();
    typename Segment::State first_new_state(first_joint_point);
    if (has_angle_wraparound && !last_curr_state.position.empty())
    {
      position_offset[0] = wraparoundJointOffset<Scalar>(last_curr_state.position[0], first_new_state.position[0],
                                                         (*options.angle_wraparound)[joint_id]);
      first_new_state = typename Segment::State(first_joint_point, position_offset);
    }

    const auto first_seg = trajectory_interface::findSegment(curr, static_cast<typename Segment::Time>(o_time.toSec()));
    const auto last_seg = trajectory_interface::findSegment(curr, last_curr_time);
    if (first_seg == curr.end() || last_seg == curr.end())
    {
      initFailed(options, "Unexpected error: Could not find segments in current trajectory.");
      return false;
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
    Segment segment(o_msg_start_time, jointPoint(*it, msg_joint), jointPoint(*next, msg_joint), position_offset);
    segment.setGoalHandle(options.rt_goal_handle);
    if (has_rt_goal_handle)
      segment.setTolerances(joint_tolerances);
    joint_result.push_back(segment);
  }
  return true;
}
/// What the result starts from: the current trajectory, whose segments from \p o_time on now
/// belong to options.rt_goal_handle, or \p n_joints empty joint trajectories without one.
template <class Trajectory>
Trajectory startingTrajectory(const InitJointTrajectoryOptions<Trajectory>& options, const ros::Time& o_time,
                              std::size_t n_joints)
{
  typedef typename Trajectory::value_type::value_type Segment;
  Trajectory result;
  if (!options.current_trajectory || options.current_trajectory->empty())
  {
    result.resize(n_joints);
    return result;
  }
  result = *options.current_trajectory;
  for (typename Trajectory::value_type& joint_traj : result)
  {
    auto active = trajectory_interface::findSegment(joint_traj, static_cast<typename Segment::Time>(o_time.toSec()));
    for (; active != joint_traj.end(); ++active)
      active->setGoalHandle(options.rt_goal_handle);
  }
  return result;
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

  const std::vector<unsigned int> mapping_vector = internal::checkedMapping(msg, joint_names, options);
  if (mapping_vector.empty())
    return Trajectory();

  SegmentTolerances<Scalar> tolerances =
      options.default_tolerances ? *options.default_tolerances : SegmentTolerances<Scalar>(joint_names.size());
  if (has_rt_goal_handle && options.rt_goal_handle->gh_.getGoal())
    updateSegmentTolerances<Scalar>(*options.rt_goal_handle->gh_.getGoal(), joint_names, tolerances);

  // First point reached after 'time' (NOTE: 'time', not 'o_time').
  const PointIter first_point = internal::firstRemainingPoint(msg, time, msg_start_time, options);
  if (first_point == msg.points.end())
    return Trajectory();

  Trajectory result = internal::startingTrajectory(options, o_time, joint_names.size());

  for (unsigned int msg_joint = 0; msg_joint < mapping_vector.size(); ++msg_joint)
  {
    const unsigned int joint_id = mapping_vector[msg_joint];
    TrajectoryPerJoint joint_result;
    if (!internal::jointSegmentsFromMessage<Trajectory>(msg, msg_joint, joint_id, first_point, o_time, o_msg_start_time,
                                                        tolerances, options, joint_result))
      return Trajectory();
    ROS_DEBUG_STREAM("Trajectory of joint " << joint_names[joint_id] << " has " << joint_result.size() << " segments.");
    if (!joint_result.empty())
      result[joint_id] = joint_result;
  }

  if (std::find_if(result.begin(), result.end(), isNotEmpty<Trajectory>) == result.end())
    result.clear();
  return result;
}

}  // namespace joint_trajectory_controller
