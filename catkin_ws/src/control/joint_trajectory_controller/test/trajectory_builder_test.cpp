// HoldTrajectoryBuilder / StopTrajectoryBuilder / TrajectoryBuilder as the original's.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <boost/make_shared.hpp>

#include <hardware_interface/joint_command_interface.h>
#include <joint_trajectory_controller/hold_trajectory_builder.h>
#include <joint_trajectory_controller/stop_trajectory_builder.h>
#include <trajectory_interface/quintic_spline_segment.h>

using namespace joint_trajectory_controller;

typedef trajectory_interface::QuinticSplineSegment<double> SegmentImpl;
typedef JointTrajectorySegment<SegmentImpl> Segment;
typedef std::vector<std::vector<Segment>> Trajectory;
typedef Segment::RealtimeGoalHandlePtr RealtimeGoalHandlePtr;

static Trajectory preallocated(unsigned int n_joints) { return Trajectory(n_joints, std::vector<Segment>(1)); }

TEST(HoldTrajectoryBuilderTest, HoldsCurrentPositions)
{
  double pos[2] = { 0.5, -1.25 }, vel[2] = { 1.0, 2.0 }, eff[2] = { 0.0, 0.0 }, cmd[2] = { 0.0, 0.0 };
  std::vector<hardware_interface::JointHandle> joints;
  joints.emplace_back(hardware_interface::JointStateHandle("j1", &pos[0], &vel[0], &eff[0]), &cmd[0]);
  joints.emplace_back(hardware_interface::JointStateHandle("j2", &pos[1], &vel[1], &eff[1]), &cmd[1]);
  HoldTrajectoryBuilder<SegmentImpl, hardware_interface::PositionJointInterface> builder(joints);

  Trajectory traj = preallocated(2);
  EXPECT_FALSE(builder.buildTrajectory(&traj));  // no start time
  builder.setStartTime(3.0);
  Trajectory wrong = preallocated(1);
  EXPECT_FALSE(builder.buildTrajectory(&wrong));  // sized for another number of joints
  Trajectory two_segments(2, std::vector<Segment>(2));
  EXPECT_FALSE(builder.buildTrajectory(&two_segments));

  pos[1] = -1.5;  // read when building
  ASSERT_TRUE(builder.buildTrajectory(&traj));
  for (unsigned int j = 0; j < 2; ++j)
  {
    EXPECT_EQ(3.0, traj[j][0].startTime());
    EXPECT_EQ(3.0, traj[j][0].endTime());
    Segment::State s;
    traj[j][0].sample(10.0, s);
    EXPECT_DOUBLE_EQ(pos[j], s.position[0]);
    EXPECT_EQ(0.0, s.velocity[0]);
    EXPECT_FALSE(traj[j][0].getGoalHandle());
  }

  actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> gh;
  RealtimeGoalHandlePtr rt_goal(new Segment::RealtimeGoalHandle(gh));
  builder.setGoalHandle(rt_goal);
  ASSERT_TRUE(builder.buildTrajectory(&traj));
  EXPECT_EQ(rt_goal, traj[0][0].getGoalHandle());
  EXPECT_EQ(rt_goal, traj[1][0].getGoalHandle());

  builder.reset();
  EXPECT_FALSE(builder.buildTrajectory(&traj));  // start time cleared
  builder.setStartTime(4.0);
  ASSERT_TRUE(builder.buildTrajectory(&traj));
  EXPECT_FALSE(traj[0][0].getGoalHandle());  // goal handle cleared
}

TEST(StopTrajectoryBuilderTest, ComesToRestInTheStopDuration)
{
  Segment::State hold_state(2);
  hold_state.position = { 1.0, -2.0 };
  hold_state.velocity = { 0.8, -0.4 };
  const double stop_duration = 0.5;
  StopTrajectoryBuilder<SegmentImpl> builder(stop_duration, hold_state);
  Trajectory traj = preallocated(2);
  EXPECT_FALSE(builder.buildTrajectory(&traj));
  builder.setStartTime(2.0);
  ASSERT_TRUE(builder.buildTrajectory(&traj));
  for (unsigned int j = 0; j < 2; ++j)
  {
    const Segment& seg = traj[j][0];
    EXPECT_EQ(2.0, seg.startTime());
    EXPECT_EQ(2.5, seg.endTime());
    Segment::State s;
    seg.sample(2.0, s);
    EXPECT_NEAR(hold_state.position[j], s.position[0], 1e-12);
    EXPECT_NEAR(hold_state.velocity[j], s.velocity[0], 1e-12);
    seg.sample(2.5, s);
    EXPECT_NEAR(0.0, s.velocity[0], 1e-9);
    // Moving on in the direction of the velocity, by less than a constant velocity would.
    const double travelled = s.position[0] - hold_state.position[j];
    EXPECT_GT(travelled * hold_state.velocity[j], 0.0);
    EXPECT_LT(std::abs(travelled), std::abs(hold_state.velocity[j]) * stop_duration);
    double prev_speed = std::abs(hold_state.velocity[j]);
    for (double t = 2.05; t < 2.5; t += 0.05)  // decelerating all the way
    {
      seg.sample(t, s);
      EXPECT_LE(std::abs(s.velocity[0]), prev_speed + 1e-12);
      prev_speed = std::abs(s.velocity[0]);
    }
  }
  Trajectory wrong = preallocated(3);
  EXPECT_FALSE(builder.buildTrajectory(&wrong));
}

namespace
{
/// Exposes the base's protected API (as a test fixture befriended by FRIEND_TEST would use it).
class FakeTrajectoryBuilder : public TrajectoryBuilder<SegmentImpl>
{
public:
  using TrajectoryBuilder<SegmentImpl>::getStartTime;
  using TrajectoryBuilder<SegmentImpl>::createGoalHandlePtr;
  using TrajectoryBuilder<SegmentImpl>::createDefaultGoalHandle;

protected:
  bool buildTrajectory(::Trajectory* /*trajectory*/) override { return true; }
};
}  // namespace

TEST(TrajectoryBuilderTest, StartTimeAndGoalHandleReference)
{
  FakeTrajectoryBuilder builder;
  EXPECT_FALSE(builder.getStartTime().is_initialized());
  builder.setStartTime(0.1);
  EXPECT_EQ(0.1, builder.getStartTime().get());
  EXPECT_FALSE(builder.createGoalHandlePtr());
  EXPECT_FALSE(FakeTrajectoryBuilder::createDefaultGoalHandle());

  actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> gh;
  RealtimeGoalHandlePtr rt_goal = boost::make_shared<Segment::RealtimeGoalHandle>(gh);
  builder.setGoalHandle(rt_goal);
  EXPECT_EQ(1, rt_goal.use_count());  // only a reference is kept
  EXPECT_EQ(rt_goal.get(), builder.createGoalHandlePtr().get());
  builder.reset();
  EXPECT_FALSE(builder.getStartTime().is_initialized());
  EXPECT_FALSE(builder.createGoalHandlePtr());
}

TEST(StopTrajectoryBuilderTest, SegmentsShareTheGoalHandle)
{
  Segment::State hold_state{ 2u };
  StopTrajectoryBuilder<SegmentImpl> builder(0.2, hold_state);
  actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> gh;
  RealtimeGoalHandlePtr rt_goal = boost::make_shared<Segment::RealtimeGoalHandle>(gh);
  builder.setStartTime(0.11)->setGoalHandle(rt_goal);
  EXPECT_EQ(1, rt_goal.use_count());
  Trajectory traj = preallocated(2);
  ASSERT_TRUE(builder.buildTrajectory(&traj));
  EXPECT_EQ(3, rt_goal.use_count());  // one per joint's segment
  Segment::State sampled{ 1 };
  traj[1][0].sample(traj[1][0].endTime(), sampled);
  EXPECT_NEAR(0.0, sampled.velocity.at(0), 1e-9);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
