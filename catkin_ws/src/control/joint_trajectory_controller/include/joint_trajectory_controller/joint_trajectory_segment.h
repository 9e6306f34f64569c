// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>

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
class GoalTracker
{
public:
  typedef actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> GoalHandle;
  enum Outcome
  {
    ACTIVE = 0,
    SUCCEEDED = 1,
    ABORTED = 2,
    FINISHED = 3
  };

  GoalTracker(const GoalHandle& gh, const std::vector<bool>& joints)
    : gh_(gh), joints_(joints), successful_(joints.size(), 0)
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
  GoalHandle gh_;
  std::vector<bool> joints_;
  std::vector<char> successful_;
  std::atomic<int> outcome_{ ACTIVE };
  int error_code_ = 0;
  const char* error_string_ = "";
};

typedef std::shared_ptr<GoalTracker> GoalTrackerPtr;

/**
 * \brief One joint's trajectory segment with the goal it belongs to (if it came through the
 * action interface) and the tolerances it must be followed with.
 */
template <class Segment>
class JointTrajectorySegment : public Segment
{
public:
  typedef typename Segment::Scalar Scalar;
  typedef typename Segment::Time Time;
  typedef typename Segment::State State;

  JointTrajectorySegment() = default;
  JointTrajectorySegment(const Time& start_time, const State& start_state, const Time& end_time,
                         const State& end_state)
    : Segment(start_time, start_state, end_time, end_state)
  {
  }

  const GoalTrackerPtr& getGoalHandle() const { return goal_; }
  void setGoalHandle(const GoalTrackerPtr& goal) { goal_ = goal; }
  const SegmentTolerancesPerJoint<Scalar>& getTolerances() const { return tolerances_; }
  void setTolerances(const SegmentTolerancesPerJoint<Scalar>& tolerances) { tolerances_ = tolerances; }

private:
  GoalTrackerPtr goal_;
  SegmentTolerancesPerJoint<Scalar> tolerances_;
};

}  // namespace joint_trajectory_controller
