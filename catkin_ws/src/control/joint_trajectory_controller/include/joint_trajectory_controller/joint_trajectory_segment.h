// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <angles/angles.h>
#include <boost/shared_ptr.hpp>

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <realtime_tools/realtime_server_goal_handle.h>
#include <ros/time.h>
#include <trajectory_msgs/JointTrajectoryPoint.h>

#include <joint_trajectory_controller/joint_trajectory_msg_utils.h>
#include <joint_trajectory_controller/tolerances.h>

namespace joint_trajectory_controller
{
/**
 * \brief An accepted follow_joint_trajectory goal as the control loop sees it.
 *
 * The control loop only ever asks for an outcome (requestSucceeded / requestAborted, lock-free);
 * the action monitor timer (action_monitor_rate) reports it through the action server.
 * A goal that was preempted or canceled is no longer active, so the loop stops checking it.
 */
class GoalTracker : public realtime_tools::RealtimeServerGoalHandle<control_msgs::FollowJointTrajectoryAction>
{
public:
  typedef actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> GoalHandle;
  typedef realtime_tools::RealtimeServerGoalHandle<control_msgs::FollowJointTrajectoryAction> Base;
  enum Outcome
  {
    ACTIVE = 0,
    SUCCEEDED = 1,
    ABORTED = 2,
    FINISHED = 3
  };

  GoalTracker(GoalHandle gh, const std::vector<bool>& joints) : Base(gh), joints_(joints), successful_(joints.size(), 0)
  {
  }

  bool isActive() const { return outcome_.load() == ACTIVE; }

  /// Control loop: ask to report success (only the first request of a goal counts).
  void requestSucceeded()
  {
    int expected = ACTIVE;
    if (outcome_.compare_exchange_strong(expected, WRITING_))
    {
      error_code_ = control_msgs::FollowJointTrajectoryResult::SUCCESSFUL;
      error_string_ = "";
      outcome_.store(SUCCEEDED);
    }
  }

  /// Control loop: ask to abort with \p error_code (\p error_string must be a literal).
  void requestAborted(int error_code, const char* error_string)
  {
    int expected = ACTIVE;
    if (outcome_.compare_exchange_strong(expected, WRITING_))
    {
      error_code_ = error_code;
      error_string_ = error_string;
      outcome_.store(ABORTED);
    }
  }

  /// Non-realtime: report a requested outcome through the action server (once; callers must not
  /// hold locks that actionlib's callbacks take). Returns true once the goal is finished.
  bool reportOutcome()
  {
    int outcome = outcome_.load();
    while (outcome == WRITING_)  // the loop is writing the result: a few instructions
      outcome = outcome_.load();
    if (outcome != SUCCEEDED && outcome != ABORTED)
      return outcome == FINISHED || outcome == REPORTING_;
    if (!outcome_.compare_exchange_strong(outcome, REPORTING_))
      return true;  // another thread reports it
    control_msgs::FollowJointTrajectoryResult result;
    result.error_code = error_code_;
    result.error_string = error_string_;
    if (outcome == SUCCEEDED)
      gh_.setSucceeded(result);
    else
      gh_.setAborted(result, error_string_);
    outcome_.store(FINISHED);
    return true;
  }

  /// Non-realtime: report a pending outcome, else cancel the goal (preemption, cancel request).
  void finish()
  {
    int expected = ACTIVE;
    if (outcome_.compare_exchange_strong(expected, REPORTING_))
    {
      control_msgs::FollowJointTrajectoryResult result;
      result.error_code = control_msgs::FollowJointTrajectoryResult::SUCCESSFUL;
      gh_.setCanceled(result);
      outcome_.store(FINISHED);
      return;
    }
    reportOutcome();
  }

  GoalHandle& goalHandle() { return gh_; }
  /// Which of the controller's joints the goal's trajectory moves.
  const std::vector<bool>& joints() const { return joints_; }
  /// Per joint: reached the goal within tolerance (written by the control loop only).
  std::vector<char>& successful() { return successful_; }

private:
  static constexpr int WRITING_ = 10;    // transient while the loop writes the result
  static constexpr int REPORTING_ = 11;  // transient while a non-realtime thread reports it
  std::vector<bool> joints_;
  std::vector<char> successful_;
  std::atomic<int> outcome_{ ACTIVE };
  int error_code_ = 0;
  const char* error_string_ = "";
};

typedef boost::shared_ptr<GoalTracker> GoalTrackerPtr;

/**
 * \brief One joint's trajectory segment (\p Segment, e.g. trajectory_interface::QuinticSplineSegment)
 * with the (realtime) goal handle it belongs to, the tolerances it must be followed with and an
 * error code, as the original's. It can be built from two trajectory_msgs points.
 *
 * The controller's own goals are GoalTracker objects (a RealtimeGoalHandle with the per-joint
 * bookkeeping of the control loop); any RealtimeGoalHandle may be attached.
 */
template <class Segment>
class JointTrajectorySegment : public Segment
{
public:
  typedef typename Segment::Scalar Scalar;
  typedef typename Segment::Time Time;

  typedef realtime_tools::RealtimeServerGoalHandle<control_msgs::FollowJointTrajectoryAction> RealtimeGoalHandle;
  typedef boost::shared_ptr<RealtimeGoalHandle> RealtimeGoalHandlePtr;

  /// The segment's state, also constructible from a trajectory point (plus position offsets).
  struct State : public Segment::State
  {
    typedef typename Segment::State::Scalar Scalar;
    State() : Segment::State() {}
    State(unsigned int size) : Segment::State(size) {}
    State(const typename Segment::State& state) : Segment::State(state) {}

    /**
     * \param point A trajectory point: its positions, and velocities and accelerations if given.
     * \param position_offset Added to the positions (wrapping of continuous joints); empty: none,
     * else one per position.
     * \throw std::invalid_argument On sizes that disagree.
     */
    State(const trajectory_msgs::JointTrajectoryPoint& point,
          const std::vector<Scalar>& position_offset = std::vector<Scalar>())
    {
      init(point, position_offset);
    }

    void init(const trajectory_msgs::JointTrajectoryPoint& point,
              const std::vector<Scalar>& position_offset = std::vector<Scalar>())
    {
      init(point, std::vector<unsigned int>(), position_offset);
    }

    /**
     * \brief As above, with the point's joints reordered: the i-th joint of the state is the
     * point's permutation[i]-th (empty: the point's order; earlier releases' API). Offsets are
     * in the state's order.
     */
    State(const trajectory_msgs::JointTrajectoryPoint& point, const std::vector<unsigned int>& permutation,
          const std::vector<Scalar>& position_offset = std::vector<Scalar>())
    {
      init(point, permutation, position_offset);
    }

    void init(const trajectory_msgs::JointTrajectoryPoint& point, const std::vector<unsigned int>& permutation,
              const std::vector<Scalar>& position_offset = std::vector<Scalar>())
    {
      const unsigned int dim = point.positions.size();
      if (!isValid(point, dim))
        throw std::invalid_argument("Size mismatch in trajectory point position, velocity or acceleration data.");
      if (!permutation.empty() && permutation.size() != dim)
        throw std::invalid_argument("Size mismatch between trajectory point and permutation vector.");
      for (unsigned int index : permutation)
        if (index >= dim)
          throw std::invalid_argument("Permutation vector contains out-of-range indices.");
      if (!position_offset.empty() && position_offset.size() != dim)
        throw std::invalid_argument(
            "Size mismatch between trajectory point "
            "and vector specifying whether joints wrap around.");
      this->position.clear();
      this->velocity.clear();
      this->acceleration.clear();
      for (unsigned int i = 0; i < dim; ++i)
      {
        const unsigned int id = permutation.empty() ? i : permutation[i];
        this->position.push_back(point.positions[id] + (position_offset.empty() ? Scalar(0) : position_offset[i]));
        if (!point.velocities.empty())
          this->velocity.push_back(point.velocities[id]);
        if (!point.accelerations.empty())
          this->acceleration.push_back(point.accelerations[id]);
      }
    }
  };

  JointTrajectorySegment() = default;

  /// Segment from \p start_state at \p start_time to \p end_state at \p end_time.
  JointTrajectorySegment(const Time& start_time, const typename Segment::State& start_state, const Time& end_time,
                         const typename Segment::State& end_state)
  {
    Segment::init(start_time, start_state, end_time, end_state);
  }

  /**
   * \brief Segment between two points of a trajectory that starts at \p traj_start_time (each
   * point is reached at traj_start_time + its time_from_start).
   * \throw std::invalid_argument If the points' sizes disagree (with each other or with
   * \p position_offset) or the segment cannot be built.
   */
  JointTrajectorySegment(const ros::Time& traj_start_time, const trajectory_msgs::JointTrajectoryPoint& start_point,
                         const trajectory_msgs::JointTrajectoryPoint& end_point,
                         const std::vector<Scalar>& position_offset = std::vector<Scalar>())
  {
    if (start_point.positions.size() != end_point.positions.size())
      throw std::invalid_argument("Can't construct segment from ROS message: Start/end points data size mismatch.");
    const Time start_time = (traj_start_time + start_point.time_from_start).toSec();
    const Time end_time = (traj_start_time + end_point.time_from_start).toSec();
    try
    {
      const State start_state(start_point, position_offset);
      const State end_state(end_point, position_offset);
      Segment::init(start_time, start_state, end_time, end_state);
    }
    catch (const std::invalid_argument& ex)
    {
      throw std::invalid_argument(std::string("Can't construct segment from ROS message: ") + ex.what());
    }
  }

  /// As above, with the points' joints reordered by \p permutation (see State; earlier releases' API).
  JointTrajectorySegment(const ros::Time& traj_start_time, const trajectory_msgs::JointTrajectoryPoint& start_point,
                         const trajectory_msgs::JointTrajectoryPoint& end_point,
                         const std::vector<unsigned int>& permutation,
                         const std::vector<Scalar>& position_offset = std::vector<Scalar>())
  {
    if (start_point.positions.size() != end_point.positions.size())
      throw std::invalid_argument("Can't construct segment from ROS message: Start/end points data size mismatch.");
    try
    {
      const State start_state(start_point, permutation, position_offset);
      const State end_state(end_point, permutation, position_offset);
      Segment::init((traj_start_time + start_point.time_from_start).toSec(), start_state,
                    (traj_start_time + end_point.time_from_start).toSec(), end_state);
    }
    catch (const std::invalid_argument& ex)
    {
      throw std::invalid_argument(std::string("Can't construct segment from ROS message: ") + ex.what());
    }
  }

  /// The (realtime) goal handle this segment belongs to (null: none).
  RealtimeGoalHandlePtr getGoalHandle() const { return rt_goal_handle_; }
  void setGoalHandle(RealtimeGoalHandlePtr rt_goal_handle) { rt_goal_handle_ = rt_goal_handle; }

  /// The tolerances this segment is followed with.
  const SegmentTolerancesPerJoint<Scalar>& getTolerances() const { return tolerances_; }
  void setTolerances(const SegmentTolerancesPerJoint<Scalar>& tolerances) { tolerances_ = tolerances; }

  /// A FollowJointTrajectoryResult error code attached to the segment (0: SUCCESSFUL).
  int getErrorCode() const { return error_code_; }
  void setErrorCode(int error_code) { error_code_ = error_code; }

private:
  RealtimeGoalHandlePtr rt_goal_handle_;
  SegmentTolerancesPerJoint<Scalar> tolerances_;
  int error_code_ = 0;
};

/**
 * \brief Offset to add to a continuous joint's new positions so that moving from \p prev_position
 * to \p next_position takes the shortest way (a half-turn goes the way the raw difference points);
 * zero if \p angle_wraparound is false.
 */
template <class Scalar>
Scalar wraparoundJointOffset(const Scalar& prev_position, const Scalar& next_position, const bool& angle_wraparound)
{
  if (!angle_wraparound)
    return Scalar(0);
  Scalar dist = angles::shortest_angular_distance(prev_position, next_position);
  if (std::abs(std::abs(dist) - M_PI) < 1e-9)
    dist = next_position > prev_position ? std::abs(dist) : -std::abs(dist);
  return (prev_position + dist) - next_position;
}

/**
 * \brief Per joint, wraparoundJointOffset(prev_position[i], next_position[i], angle_wraparound[i])
 * (earlier releases' API); empty if the sizes disagree.
 */
template <class Scalar>
std::vector<Scalar> wraparoundOffset(const std::vector<Scalar>& prev_position, const std::vector<Scalar>& next_position,
                                     const std::vector<bool>& angle_wraparound)
{
  const std::size_t n = angle_wraparound.size();
  if (prev_position.size() != n || next_position.size() != n)
    return std::vector<Scalar>();
  std::vector<Scalar> offset(n, Scalar(0));
  for (std::size_t i = 0; i < n; ++i)
    offset[i] = wraparoundJointOffset<Scalar>(prev_position[i], next_position[i], angle_wraparound[i]);
  return offset;
}

}  // namespace joint_trajectory_controller
