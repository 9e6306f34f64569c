// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <vector>

#include <joint_trajectory_controller/trajectory_builder.h>

namespace joint_trajectory_controller
{
/**
 * \brief Builds a trajectory that holds every joint at its current position (read from the joint
 * handles when buildTrajectory() runs): one zero-duration segment per joint at rest.
 */
template <class SegmentImpl, class HardwareInterface>
class HoldTrajectoryBuilder : public TrajectoryBuilder<SegmentImpl>
{
private:
  using Segment = JointTrajectorySegment<SegmentImpl>;
  using TrajectoryPerJoint = std::vector<Segment>;
  using Trajectory = std::vector<TrajectoryPerJoint>;
  using RealtimeGoalHandlePtr =
      boost::shared_ptr<realtime_tools::RealtimeServerGoalHandle<control_msgs::FollowJointTrajectoryAction>>;
  using JointHandle = typename HardwareInterface::ResourceHandleType;

public:
  /// \p joints is referenced, not copied: it must outlive the builder.
  HoldTrajectoryBuilder(const std::vector<JointHandle>& joints) : joints_(joints) {}

  bool buildTrajectory(Trajectory* hold_traj) override
  {
    if (!this->getStartTime())
      return false;
    if (!TrajectoryBuilder<SegmentImpl>::isTrajectoryValid(hold_traj, joints_.size(), 1))
      return false;
    const typename Segment::Time start_time = this->getStartTime().value();
    RealtimeGoalHandlePtr goal_handle = this->createGoalHandlePtr();
    for (unsigned int j = 0; j < joints_.size(); ++j)
    {
      state_.position[0] = joints_[j].getPosition();
      state_.velocity[0] = 0.0;
      state_.acceleration[0] = 0.0;
      Segment& segment = (*hold_traj)[j].front();
      segment.init(start_time, state_, start_time, state_);
      segment.setGoalHandle(goal_handle);
    }
    return true;
  }

private:
  const std::vector<JointHandle>& joints_;
  typename Segment::State state_{ typename Segment::State(1) };  // preallocated for the realtime loop
};

}  // namespace joint_trajectory_controller
