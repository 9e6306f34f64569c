// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <vector>

#include <joint_trajectory_controller/trajectory_builder.h>

namespace joint_trajectory_controller
{
/**
 * \brief Builds a trajectory that brings every joint from \p hold_state (position, velocity) to
 * rest in \p stop_traj_duration seconds.
 *
 * As the original: a segment from (p, v) to (p, -v) over twice the duration is symmetric, so its
 * midpoint has zero velocity; each joint's segment goes from (p, v) to that midpoint state in the
 * stop duration.
 */
template <class SegmentImpl>
class StopTrajectoryBuilder : public TrajectoryBuilder<SegmentImpl>
{
private:
  using Segment = JointTrajectorySegment<SegmentImpl>;
  using TrajectoryPerJoint = std::vector<Segment>;
  using Trajectory = std::vector<TrajectoryPerJoint>;
  using RealtimeGoalHandlePtr =
      boost::shared_ptr<realtime_tools::RealtimeServerGoalHandle<control_msgs::FollowJointTrajectoryAction>>;

public:
  /// \p hold_state (one entry per joint) is referenced, not copied: it must outlive the builder.
  StopTrajectoryBuilder(const typename Segment::Time& stop_traj_duration, const typename Segment::State& hold_state)
    : stop_traj_duration_(stop_traj_duration), hold_state_(hold_state)
  {
  }

  bool buildTrajectory(Trajectory* hold_traj) override
  {
    const unsigned int n_joints = hold_state_.position.size();
    if (!this->getStartTime())
      return false;
    if (!TrajectoryBuilder<SegmentImpl>::isTrajectoryValid(hold_traj, n_joints, 1))
      return false;
    const typename Segment::Time start_time = this->getStartTime().value();
    const typename Segment::Time end_time = start_time + stop_traj_duration_;
    const typename Segment::Time end_time_2x = start_time + 2.0 * stop_traj_duration_;
    RealtimeGoalHandlePtr goal_handle = this->createGoalHandlePtr();
    for (unsigned int j = 0; j < n_joints; ++j)
    {
      start_state_.position[0] = hold_state_.position[j];
      start_state_.velocity[0] = hold_state_.velocity[j];
      start_state_.acceleration[0] = 0.0;
      end_state_.position[0] = hold_state_.position[j];
      end_state_.velocity[0] = -hold_state_.velocity[j];
      end_state_.acceleration[0] = 0.0;

      Segment& segment = (*hold_traj)[j].front();
      segment.init(start_time, start_state_, end_time_2x, end_state_);
      segment.sample(end_time, end_state_);  // the midpoint: at rest
      segment.init(start_time, start_state_, end_time, end_state_);
      segment.setGoalHandle(goal_handle);
    }
    return true;
  }

private:
  const typename Segment::Time stop_traj_duration_;
  const typename Segment::State& hold_state_;
  typename Segment::State start_state_{ typename Segment::State(1) };  // preallocated for the realtime loop
  typename Segment::State end_state_{ typename Segment::State(1) };
};

}  // namespace joint_trajectory_controller
