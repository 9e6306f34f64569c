// JointTrajectorySegment's original API: construction from trajectory_msgs points (with position
// offsets), the original's exceptions on size mismatches, goal handle, tolerances, error code.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include <joint_trajectory_controller/joint_trajectory_segment.h>
#include <trajectory_interface/quintic_spline_segment.h>

using namespace joint_trajectory_controller;
using trajectory_msgs::JointTrajectoryPoint;

typedef JointTrajectorySegment<trajectory_interface::QuinticSplineSegment<double>> Segment;

class JointTrajectorySegmentTest : public ::testing::Test
{
protected:
  JointTrajectorySegmentTest() : traj_start_time(0.5)
  {
    p_start.positions.assign(1, 2.0);
    p_start.velocities.assign(1, -1.0);
    p_start.time_from_start = ros::Duration(1.0);
    p_end.positions.assign(1, 4.0);
    p_end.velocities.assign(1, -2.0);
    p_end.time_from_start = ros::Duration(2.0);
  }
  ros::Time traj_start_time;
  JointTrajectoryPoint p_start, p_end;
};

TEST_F(JointTrajectorySegmentTest, InvalidSegmentConstruction)
{
  EXPECT_THROW(Segment(traj_start_time, JointTrajectoryPoint(), p_end), std::invalid_argument);
  JointTrajectoryPoint bad = p_start;
  bad.positions.push_back(0.0);  // start/end size mismatch
  EXPECT_THROW(Segment(traj_start_time, bad, p_end), std::invalid_argument);
  bad = p_start;
  bad.velocities.push_back(0.0);  // invalid start state
  EXPECT_THROW(Segment(traj_start_time, bad, p_end), std::invalid_argument);
  bad = p_end;
  bad.accelerations.assign(3, 0.0);  // invalid end state
  EXPECT_THROW(Segment(traj_start_time, p_start, bad), std::invalid_argument);
  EXPECT_THROW(Segment(traj_start_time, p_start, p_end, std::vector<double>(2, 0.0)), std::invalid_argument);
  try
  {
    Segment(traj_start_time, p_start, p_end, std::vector<double>(2, 0.0));
  }
  catch (const std::invalid_argument& ex)
  {
    EXPECT_NE(std::string::npos, std::string(ex.what()).find("Can't construct segment from ROS message"));
  }
}

TEST_F(JointTrajectorySegmentTest, ValidSegmentConstructionRos)
{
  const Segment segment(traj_start_time, p_start, p_end);
  EXPECT_EQ((traj_start_time + p_start.time_from_start).toSec(), segment.startTime());
  EXPECT_EQ((traj_start_time + p_end.time_from_start).toSec(), segment.endTime());
  Segment::State state;
  segment.sample(segment.startTime(), state);
  EXPECT_NEAR(2.0, state.position[0], 1e-12);
  EXPECT_NEAR(-1.0, state.velocity[0], 1e-12);
  segment.sample(segment.endTime(), state);
  EXPECT_NEAR(4.0, state.position[0], 1e-12);
  EXPECT_NEAR(-2.0, state.velocity[0], 1e-12);
  EXPECT_FALSE(segment.getGoalHandle());
  EXPECT_EQ(0, segment.getErrorCode());
}

TEST_F(JointTrajectorySegmentTest, ValidSegmentConstructionStates)
{
  const Segment::State start(p_start), end(p_end);
  const Segment segment(1.5, start, 2.5, end);
  Segment::State state;
  segment.sample(2.5, state);
  EXPECT_NEAR(4.0, state.position[0], 1e-12);
  EXPECT_EQ(1.5, segment.startTime());
}

TEST_F(JointTrajectorySegmentTest, PositionOffset)
{
  const Segment segment(traj_start_time, p_start, p_end, std::vector<double>(1, -2.0 * M_PI));
  Segment::State state;
  segment.sample(segment.startTime(), state);
  EXPECT_NEAR(2.0 - 2.0 * M_PI, state.position[0], 1e-12);
  EXPECT_NEAR(-1.0, state.velocity[0], 1e-12);  // offsets apply to positions only
  segment.sample(segment.endTime(), state);
  EXPECT_NEAR(4.0 - 2.0 * M_PI, state.position[0], 1e-12);
}

TEST_F(JointTrajectorySegmentTest, StateFromPoint)
{
  JointTrajectoryPoint p;
  p.positions = { 1.0, 2.0 };
  const Segment::State s(p);
  ASSERT_EQ(2u, s.position.size());
  EXPECT_TRUE(s.velocity.empty());  // not given, not invented
  EXPECT_TRUE(s.acceleration.empty());
  p.velocities = { 0.5 };
  EXPECT_THROW(Segment::State{ p }, std::invalid_argument);
}

TEST_F(JointTrajectorySegmentTest, GoalHandleTolerancesErrorCode)
{
  typedef actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> GoalHandle;
  GoalHandle gh;
  Segment::RealtimeGoalHandlePtr rt_goal(new Segment::RealtimeGoalHandle(gh));
  Segment segment(traj_start_time, p_start, p_end);
  segment.setGoalHandle(rt_goal);
  EXPECT_EQ(rt_goal, segment.getGoalHandle());

  SegmentTolerancesPerJoint<double> tols;
  tols.state_tolerance.position = 0.1;
  tols.goal_state_tolerance.velocity = 0.2;
  tols.goal_time_tolerance = 1.5;
  segment.setTolerances(tols);
  EXPECT_EQ(0.1, segment.getTolerances().state_tolerance.position);
  EXPECT_EQ(0.2, segment.getTolerances().goal_state_tolerance.velocity);
  EXPECT_EQ(1.5, segment.getTolerances().goal_time_tolerance);

  segment.setErrorCode(control_msgs::FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED);
  EXPECT_EQ(control_msgs::FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED, segment.getErrorCode());
}

TEST_F(JointTrajectorySegmentTest, PermutationOfEarlierReleases)
{
  p_start.positions.push_back(-p_start.positions[0]);
  p_start.velocities.push_back(-p_start.velocities[0]);
  p_end.positions.push_back(-p_end.positions[0]);
  p_end.velocities.push_back(-p_end.velocities[0]);
  Segment::State s;
  const Segment same(traj_start_time, p_start, p_end, std::vector<unsigned int>{ 0, 1 });
  same.sample(same.startTime(), s);
  EXPECT_EQ(p_start.positions[0], s.position[0]);
  EXPECT_EQ(p_start.positions[1], s.position[1]);
  const Segment swapped(traj_start_time, p_start, p_end, std::vector<unsigned int>{ 1, 0 });
  swapped.sample(swapped.startTime(), s);
  EXPECT_EQ(p_start.positions[1], s.position[0]);
  EXPECT_EQ(p_start.positions[0], s.position[1]);
  EXPECT_EQ(p_start.velocities[1], s.velocity[0]);
  EXPECT_THROW(Segment(traj_start_time, p_start, p_end, std::vector<unsigned int>(1, 0)), std::invalid_argument);
  EXPECT_THROW(Segment(traj_start_time, p_start, p_end, std::vector<unsigned int>(2, 2)), std::invalid_argument);
  EXPECT_THROW(Segment(traj_start_time, p_start, p_end, std::vector<unsigned int>(), std::vector<double>(3, 0.0)),
               std::invalid_argument);
}

TEST(WraparoundOffsetTest, PerJointVectors)
{
  const double half_pi = M_PI / 2.0, two_pi = 2.0 * M_PI;
  const std::vector<double> pos1 = { half_pi / 2.0, half_pi / 2.0 };
  const std::vector<double> pos2 = { two_pi + half_pi, 2.0 * two_pi + half_pi };
  std::vector<double> off = wraparoundOffset(pos1, pos2, std::vector<bool>{ true, false });
  ASSERT_EQ(2u, off.size());
  EXPECT_NEAR(-two_pi, off[0], 1e-9);
  EXPECT_NEAR(0.0, off[1], 1e-9);
  off = wraparoundOffset<double>(pos2, pos1, std::vector<bool>(2, true));
  EXPECT_NEAR(two_pi, off[0], 1e-9);
  EXPECT_NEAR(2.0 * two_pi, off[1], 1e-9);
  EXPECT_TRUE(wraparoundOffset(pos1, pos2, std::vector<bool>(3, true)).empty());
}

TEST(WraparoundJointOffsetTest, WrappingAndNot)
{
  const double half_pi = M_PI / 2.0, two_pi = 2.0 * M_PI;
  EXPECT_NEAR(0.0, wraparoundJointOffset(half_pi / 2.0, two_pi + half_pi, false), 1e-12);
  EXPECT_NEAR(-two_pi, wraparoundJointOffset(half_pi / 2.0, two_pi + half_pi, true), 1e-9);
  EXPECT_NEAR(two_pi, wraparoundJointOffset(two_pi + half_pi, half_pi / 2.0, true), 1e-9);
  EXPECT_NEAR(-2.0 * two_pi, wraparoundJointOffset(half_pi / 2.0, 2.0 * two_pi + half_pi, true), 1e-9);
  EXPECT_NEAR(0.0, wraparoundJointOffset(half_pi / 2.0, M_PI, true), 1e-9);
  // A half turn goes the way the raw difference points.
  EXPECT_NEAR(0.0, wraparoundJointOffset(0.0, M_PI, true), 1e-9);
  EXPECT_NEAR(0.0, wraparoundJointOffset(0.0, -M_PI, true), 1e-9);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
