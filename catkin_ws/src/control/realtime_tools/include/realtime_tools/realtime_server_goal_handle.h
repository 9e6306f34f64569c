// Re-implementation of ros-controls/realtime_tools (ROS 1 API) for Debian 12.
#pragma once

#include <cstdint>

#include <boost/shared_ptr.hpp>

#include <actionlib/server/action_server.h>
#include <actionlib_msgs/GoalStatus.h>
#include <ros/timer.h>

namespace realtime_tools
{
/**
 * \brief An actionlib server goal handle a realtime loop may finish without calling actionlib.
 *
 * The realtime side only records a request (setAborted / setCanceled / setSucceeded, the first
 * one of a goal wins; setFeedback replaces the pending feedback). A non-realtime timer calls
 * runNonRealtime(), which forwards the request to the goal handle when the goal's status allows
 * it: abort and succeed while ACTIVE or PREEMPTING, cancel while PREEMPTING, feedback while
 * ACTIVE. preallocated_result_ and preallocated_feedback_ are allocated up front (or taken from
 * the constructor) so the realtime side can fill them without allocating.
 */
template <class Action>
class RealtimeServerGoalHandle
{
private:
  ACTION_DEFINITION(Action);  // Result, ResultPtr, ResultConstPtr, Feedback, FeedbackPtr, ...

  typedef actionlib::ServerGoalHandle<Action> GoalHandle;

public:
  bool req_abort_;
  bool req_cancel_;
  bool req_succeed_;
  ResultConstPtr req_result_;
  FeedbackConstPtr req_feedback_;

  GoalHandle gh_;
  ResultPtr preallocated_result_;      ///< for the realtime side to fill and pass to setX()
  FeedbackPtr preallocated_feedback_;  ///< for the realtime side to fill and pass to setFeedback()

  explicit RealtimeServerGoalHandle(GoalHandle& gh, const ResultPtr& preallocated_result = ResultPtr(),
                                    const FeedbackPtr& preallocated_feedback = FeedbackPtr())
    : req_abort_(false)
    , req_cancel_(false)
    , req_succeed_(false)
    , gh_(gh)
    , preallocated_result_(preallocated_result ? preallocated_result : ResultPtr(new Result))
    , preallocated_feedback_(preallocated_feedback ? preallocated_feedback : FeedbackPtr(new Feedback))
  {
  }

  virtual ~RealtimeServerGoalHandle() = default;

  /// Request aborting the goal with \p result (none: actionlib's default result).
  void setAborted(ResultConstPtr result = ResultConstPtr())
  {
    if (noRequestYet())
    {
      req_result_ = result;
      req_abort_ = true;
    }
  }

  /// Request canceling the goal (honoured once the goal is PREEMPTING).
  void setCanceled(ResultConstPtr result = ResultConstPtr())
  {
    if (noRequestYet())
    {
      req_result_ = result;
      req_cancel_ = true;
    }
  }

  /// Request reporting success.
  void setSucceeded(ResultConstPtr result = ResultConstPtr())
  {
    if (noRequestYet())
    {
      req_result_ = result;
      req_succeed_ = true;
    }
  }

  /// Feedback to publish at the next runNonRealtime() while the goal is ACTIVE.
  void setFeedback(FeedbackConstPtr feedback = FeedbackConstPtr()) { req_feedback_ = feedback; }

  /// True if the handle refers to a goal.
  bool valid() { return gh_.getGoal() != nullptr; }

  /// Non-realtime: forward the pending request and feedback to actionlib (timer callback).
  void runNonRealtime(const ros::TimerEvent& /*te*/)
  {
    if (!valid())
      return;
    using actionlib_msgs::GoalStatus;
    const uint8_t status = gh_.getGoalStatus().status;
    const bool active_or_preempting = status == GoalStatus::ACTIVE || status == GoalStatus::PREEMPTING;
    if (req_abort_ && active_or_preempting)
    {
      if (req_result_)
        gh_.setAborted(*req_result_);
      else
        gh_.setAborted();
    }
    else if (req_cancel_ && status == GoalStatus::PREEMPTING)
    {
      if (req_result_)
        gh_.setCanceled(*req_result_);
      else
        gh_.setCanceled();
    }
    else if (req_succeed_ && active_or_preempting)
    {
      if (req_result_)
        gh_.setSucceeded(*req_result_);
      else
        gh_.setSucceeded();
    }
    if (req_feedback_ && status == GoalStatus::ACTIVE)  // the status before this call, as the original
      gh_.publishFeedback(*req_feedback_);
  }

private:
  bool noRequestYet() const { return !req_succeed_ && !req_abort_ && !req_cancel_; }
};

}  // namespace realtime_tools
