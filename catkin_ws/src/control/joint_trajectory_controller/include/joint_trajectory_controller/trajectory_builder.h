// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <vector>

#include <boost/optional.hpp>
#include <boost/shared_ptr.hpp>

#include <control_msgs/FollowJointTrajectoryAction.h>
#include <realtime_tools/realtime_server_goal_handle.h>

#include <joint_trajectory_controller/joint_trajectory_segment.h>

namespace joint_trajectory_controller
{
/**
 * \brief Base of the builders of special trajectories (hold, stop). Use:
 * \code
 * builder.setStartTime(start_time);
 * builder.setGoalHandle(goal_handle);   // optional
 * builder.buildTrajectory(&trajectory); // trajectory preallocated: one segment per joint
 * \endcode
 * The start time is required; reset() clears start time and goal handle.
 */
template <class SegmentImpl>
class TrajectoryBuilder
{
public:
  virtual ~TrajectoryBuilder() = default;

private:
  using Segment = JointTrajectorySegment<SegmentImpl>;
  using TrajectoryPerJoint = std::vector<Segment>;
  using Trajectory = std::vector<TrajectoryPerJoint>;
  using RealtimeGoalHandle = realtime_tools::RealtimeServerGoalHandle<control_msgs::FollowJointTrajectoryAction>;
  using RealtimeGoalHandlePtr = boost::shared_ptr<RealtimeGoalHandle>;

public:
  /// Start time [s] of the trajectory to build (cleared by reset()).
  TrajectoryBuilder<SegmentImpl>* setStartTime(const typename Segment::Time& start_time)
  {
    start_time_ = start_time;
    return this;
  }

  /// Goal handle attached to the built segments; only a reference is kept (cleared by reset()).
  TrajectoryBuilder<SegmentImpl>* setGoalHandle(RealtimeGoalHandlePtr& goal_handle)
  {
    goal_handle_ = goal_handle;
    return this;
  }

  /// Clear what must not carry over to the next buildTrajectory().
  virtual void reset()
  {
    start_time_ = boost::none;
    goal_handle_ = boost::none;
  }

  /// Fill \p trajectory; false if it cannot (no start time, trajectory not sized properly).
  virtual bool buildTrajectory(Trajectory* trajectory) = 0;

protected:
  /// The goal handle set, or a null one.
  RealtimeGoalHandlePtr createGoalHandlePtr() const
  {
    return goal_handle_ ? goal_handle_.value() : createDefaultGoalHandle();
  }

  const boost::optional<typename Segment::Time>& getStartTime() const { return start_time_; }

  static RealtimeGoalHandlePtr createDefaultGoalHandle() { return RealtimeGoalHandlePtr(); }

  /// True if \p trajectory has \p expected_number_of_joints entries of \p expected_number_of_segments segments.
  static bool isTrajectoryValid(const Trajectory* trajectory, const unsigned int expected_number_of_joints,
                                const unsigned int expected_number_of_segments)
  {
    if (!trajectory || trajectory->size() != expected_number_of_joints)
      return false;
    for (const TrajectoryPerJoint& per_joint : *trajectory)
      if (per_joint.size() != expected_number_of_segments)
        return false;
    return true;
  }

private:
  boost::optional<typename Segment::Time> start_time_{ boost::none };
  boost::optional<RealtimeGoalHandlePtr&> goal_handle_{ boost::none };
};

}  // namespace joint_trajectory_controller
