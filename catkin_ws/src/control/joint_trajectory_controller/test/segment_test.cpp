// Segments, tolerances and trajectory building of the joint trajectory controller, without ROS
// communication: spline order by what the points give, sampling outside a segment, wrapping of
// continuous joints, refusal of bad messages with the action's error codes, replacement of the
// future part of the current trajectory, the stop ramp.
#include <cmath>

#include <gtest/gtest.h>

#include <joint_trajectory_controller/init_joint_trajectory.h>
#include <joint_trajectory_controller/tolerances.h>
#include <trajectory_interface/pos_vel_acc_eff_state.h>
#include <trajectory_interface/quintic_spline_segment.h>

using namespace joint_trajectory_controller;
typedef trajectory_interface::QuinticSplineSegment<double> Segment;
typedef Segment::State State;
typedef control_msgs::FollowJointTrajectoryResult Result;

static State state(double p, std::vector<double> v = {}, std::vector<double> a = {})
{
  State s;
  s.position = { p };
  s.velocity = v;
  s.acceleration = a;
  return s;
}

TEST(QuinticSplineSegmentTest, LinearWhenOnlyPositions)
{
  Segment seg(1.0, state(0.0), 3.0, state(2.0));
  State s;
  seg.sample(2.0, s);
  EXPECT_DOUBLE_EQ(1.0, s.position[0]);
  EXPECT_DOUBLE_EQ(1.0, s.velocity[0]);  // constant velocity
  EXPECT_DOUBLE_EQ(0.0, s.acceleration[0]);
  seg.sample(1.5, s);
  EXPECT_DOUBLE_EQ(0.5, s.position[0]);
  seg.sample(4.0, s);  // past the end: at rest at the end position
  EXPECT_DOUBLE_EQ(2.0, s.position[0]);
  EXPECT_DOUBLE_EQ(0.0, s.velocity[0]);
  EXPECT_DOUBLE_EQ(1.0, seg.startTime());
  EXPECT_DOUBLE_EQ(3.0, seg.endTime());
  EXPECT_EQ(1u, seg.size());
}

TEST(QuinticSplineSegmentTest, CubicWhenVelocitiesMeetBoundaryConditions)
{
  Segment seg(0.0, state(0.0, { 1.0 }), 2.0, state(1.0, { -0.5 }));
  State s;
  seg.sample(0.0, s);
  EXPECT_NEAR(0.0, s.position[0], 1e-12);
  EXPECT_NEAR(1.0, s.velocity[0], 1e-12);
  seg.sample(2.0, s);
  EXPECT_NEAR(1.0, s.position[0], 1e-12);
  EXPECT_NEAR(-0.5, s.velocity[0], 1e-12);
  // A cubic has a constant third derivative: acceleration is linear in time.
  State s1, s2, s3;
  seg.sample(0.5, s1);
  seg.sample(1.0, s2);
  seg.sample(1.5, s3);
  EXPECT_NEAR(s2.acceleration[0] - s1.acceleration[0], s3.acceleration[0] - s2.acceleration[0], 1e-12);
}

TEST(QuinticSplineSegmentTest, QuinticMeetsAllBoundaryConditions)
{
  Segment seg(0.0, state(0.5, { 0.2 }, { -1.0 }), 1.5, state(-1.0, { 0.3 }, { 2.0 }));
  State s;
  seg.sample(0.0, s);
  EXPECT_NEAR(0.5, s.position[0], 1e-12);
  EXPECT_NEAR(0.2, s.velocity[0], 1e-12);
  EXPECT_NEAR(-1.0, s.acceleration[0], 1e-12);
  seg.sample(1.5, s);
  EXPECT_NEAR(-1.0, s.position[0], 1e-9);
  EXPECT_NEAR(0.3, s.velocity[0], 1e-9);
  EXPECT_NEAR(2.0, s.acceleration[0], 1e-9);
  // Velocity is the derivative of position.
  State a, b;
  seg.sample(0.7, a);
  seg.sample(0.7 + 1e-6, b);
  EXPECT_NEAR(a.velocity[0], (b.position[0] - a.position[0]) / 1e-6, 1e-4);
}

TEST(QuinticSplineSegmentTest, ReproducesPolynomials)
{
  // x^3 - 2x on [0, 2] (time shifted by 1): a cubic from its end positions and velocities.
  Segment cubic(1.0, state(0.0, { -2.0 }), 3.0, state(4.0, { 10.0 }));
  State s;
  cubic.sample(1.0 + std::sqrt(2.0), s);
  EXPECT_NEAR(0.0, s.position[0], 1e-9);
  EXPECT_NEAR(4.0, s.velocity[0], 1e-9);
  EXPECT_NEAR(6.0 * std::sqrt(2.0), s.acceleration[0], 1e-9);
  cubic.sample(3.0, s);
  EXPECT_NEAR(12.0, s.acceleration[0], 1e-9);
  // x(x-1)(x-2)(x-3)(x-4) on [0, 2]: a quintic from positions, velocities and accelerations.
  Segment quintic(1.0, state(0.0, { 24.0 }, { -100.0 }), 3.0, state(0.0, { 4.0 }, { 0.0 }));
  quintic.sample(2.0, s);
  EXPECT_NEAR(0.0, s.position[0], 1e-9);
  EXPECT_NEAR(-6.0, s.velocity[0], 1e-9);
  EXPECT_NEAR(10.0, s.acceleration[0], 1e-9);
}

TEST(QuinticSplineSegmentTest, SamplingOutsideTheSegment)
{
  Segment seg(1.0, state(0.0, { 1.0 }, { 0.0 }), 2.0, state(1.0, { 0.5 }, { 0.0 }));
  State s;
  seg.sample(0.0, s);  // before: start position, at rest
  EXPECT_DOUBLE_EQ(0.0, s.position[0]);
  EXPECT_DOUBLE_EQ(0.0, s.velocity[0]);
  seg.sample(5.0, s);  // after: at rest at the end position
  EXPECT_NEAR(1.0, s.position[0], 1e-12);
  EXPECT_DOUBLE_EQ(0.0, s.velocity[0]);
  EXPECT_DOUBLE_EQ(0.0, s.acceleration[0]);
  seg.sample(2.0, s);  // at the end: the end state
  EXPECT_NEAR(0.5, s.velocity[0], 1e-12);
}

TEST(QuinticSplineSegmentTest, BadArguments)
{
  EXPECT_THROW(Segment(2.0, state(0.0), 1.0, state(1.0)), std::invalid_argument);
  State two;
  two.position = { 0.0, 1.0 };
  EXPECT_THROW(Segment(0.0, state(0.0), 1.0, two), std::invalid_argument);
  Segment zero(1.0, state(0.0, { 2.0 }), 1.0, state(3.0, { 4.0 }));  // zero duration: its start state
  State s;
  zero.sample(1.0, s);
  EXPECT_DOUBLE_EQ(0.0, s.position[0]);
  EXPECT_DOUBLE_EQ(2.0, s.velocity[0]);
  zero.sample(2.0, s);
  EXPECT_DOUBLE_EQ(0.0, s.position[0]);
  EXPECT_DOUBLE_EQ(0.0, s.velocity[0]);
  Segment none;  // default-constructed: samples nothing
  none.sample(1.0, s);
  EXPECT_TRUE(s.position.empty());
}

TEST(TolerancesTest, ZeroIsNotEnforcedNegativeDisables)
{
  State err = state(0.1, { 0.02 });
  StateTolerances<double> tol(0.05, 0.0);
  EXPECT_FALSE(checkStateTolerancePerJoint(err, tol));
  tol.position = 0.2;
  EXPECT_TRUE(checkStateTolerancePerJoint(err, tol));
  tol.velocity = 0.01;
  EXPECT_FALSE(checkStateTolerancePerJoint(err, tol));
  tol = StateTolerances<double>();
  EXPECT_TRUE(checkStateTolerancePerJoint(err, tol));

  // Per joint, over a state of several joints (as the original's PosVelAccEffState).
  trajectory_interface::PosVelAccEffState<double> errs(2);
  errs.position = { 0.01, -0.3 };
  std::vector<StateTolerances<double>> per_joint(2, StateTolerances<double>(0.1));
  EXPECT_FALSE(checkStateTolerance(errs, per_joint));
  per_joint[1].position = 0.5;
  EXPECT_TRUE(checkStateTolerance(errs, per_joint));
  per_joint[1].position = -1.0;  // not positive: not enforced
  errs.position[1] = 10.0;
  EXPECT_TRUE(checkStateTolerance(errs, per_joint));

  SegmentTolerances<double> tols(2);
  tols.state_tolerance[0].position = 0.05;
  tols.goal_time_tolerance = 0.5;
  control_msgs::FollowJointTrajectoryGoal goal;
  goal.path_tolerance.resize(2);
  goal.path_tolerance[0].name = "j1";
  goal.path_tolerance[0].position = -1.0;  // disable
  goal.path_tolerance[1].name = "j2";
  goal.path_tolerance[1].position = 0.3;
  goal.goal_tolerance.resize(1);
  goal.goal_tolerance[0].name = "j2";
  goal.goal_tolerance[0].velocity = 0.0;  // keep default
  goal.goal_tolerance[0].position = 0.02;
  goal.goal_time_tolerance = ros::Duration(0.0);  // keep default
  updateSegmentTolerances<double>(goal, { "j1", "j2" }, tols);
  EXPECT_DOUBLE_EQ(0.0, tols.state_tolerance[0].position);
  EXPECT_DOUBLE_EQ(0.3, tols.state_tolerance[1].position);
  EXPECT_DOUBLE_EQ(0.02, tols.goal_state_tolerance[1].position);
  EXPECT_DOUBLE_EQ(0.5, tols.goal_time_tolerance);
  goal.goal_time_tolerance = ros::Duration(1.5);
  updateSegmentTolerances<double>(goal, { "j1", "j2" }, tols);
  EXPECT_DOUBLE_EQ(1.5, tols.goal_time_tolerance);
}

TEST(WraparoundTest, ShortestWayAndHalfTurn)
{
  EXPECT_DOUBLE_EQ(0.0, wraparoundJointOffset(0.25 * M_PI, 4.5 * M_PI, false));
  // 0.25 pi -> 4.5 pi (= 0.5 pi): a quarter of a turn forward, so the offset is -4 pi.
  EXPECT_NEAR(-4.0 * M_PI, wraparoundJointOffset(0.25 * M_PI, 4.5 * M_PI, true), 1e-9);
  EXPECT_NEAR(2.0 * M_PI, wraparoundJointOffset(0.5 * M_PI, -1.75 * M_PI, true), 1e-9);
  // A half turn goes the way of the raw difference: no offset either way.
  EXPECT_NEAR(0.0, wraparoundJointOffset(-M_PI / 2.0, M_PI / 2.0, true), 1e-9);
  EXPECT_NEAR(0.0, wraparoundJointOffset(M_PI / 2.0, -M_PI / 2.0, true), 1e-9);
}

class InitTrajectoryTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    joint_names = { "j1", "j2" };
    wrap = { false, true };
    current = holdTrajectory<Segment>(nullptr, { 0.0, 0.0 }, 0.0, 0.0);
    options.current_trajectory = &current;
    options.joint_names = &joint_names;
    options.angle_wraparound = &wrap;
    msg.joint_names = joint_names;
    trajectory_msgs::JointTrajectoryPoint p;
    p.positions = { 1.0, 1.0 };
    p.time_from_start = ros::Duration(1.0);
    msg.points.push_back(p);
    p.positions = { 2.0, 3.0 };
    p.time_from_start = ros::Duration(2.0);
    msg.points.push_back(p);
  }
  std::vector<std::string> joint_names;
  std::vector<bool> wrap;
  SegmentsPerJoint<Segment> current;
  UpdateJointTrajectoryOptions<Segment> options;
  trajectory_msgs::JointTrajectory msg;
  TrajectoryError error;
};

TEST_F(InitTrajectoryTest, BridgeAndPoints)
{
  const SegmentsPerJoint<Segment> traj = updateJointTrajectory<Segment>(msg, ros::Time(10.0), options, error);
  ASSERT_EQ(2u, traj.size());
  EXPECT_EQ(0, error.error_code);
  State s;
  sampleJointTrajectory<Segment>(traj[0], 10.0, s);
  EXPECT_NEAR(0.0, s.position[0], 1e-12);
  sampleJointTrajectory<Segment>(traj[0], 11.0, s);
  EXPECT_NEAR(1.0, s.position[0], 1e-12);
  sampleJointTrajectory<Segment>(traj[0], 11.5, s);
  EXPECT_NEAR(1.5, s.position[0], 1e-12);  // positions only: linear
  sampleJointTrajectory<Segment>(traj[1], 12.0, s);
  EXPECT_NEAR(3.0, s.position[0], 1e-12);
  sampleJointTrajectory<Segment>(traj[1], 20.0, s);
  EXPECT_NEAR(3.0, s.position[0], 1e-12);
}

TEST_F(InitTrajectoryTest, ReplacesOnlyTheFuture)
{
  current = updateJointTrajectory<Segment>(msg, ros::Time(10.0), options, error);
  // A new trajectory starting at 11.5 keeps the current one until then.
  trajectory_msgs::JointTrajectory next = msg;
  next.header.stamp = ros::Time(11.5);
  next.points.resize(1);
  next.points[0].positions = { -1.0, 0.0 };
  next.points[0].time_from_start = ros::Duration(1.0);
  const SegmentsPerJoint<Segment> traj = updateJointTrajectory<Segment>(next, ros::Time(10.5), options, error);
  ASSERT_EQ(2u, traj.size());
  State s;
  sampleJointTrajectory<Segment>(traj[0], 11.0, s);
  EXPECT_NEAR(1.0, s.position[0], 1e-12);  // still the current trajectory
  sampleJointTrajectory<Segment>(traj[0], 11.5, s);
  EXPECT_NEAR(1.5, s.position[0], 1e-12);  // the bridge starts where the current one is
  sampleJointTrajectory<Segment>(traj[0], 12.5, s);
  EXPECT_NEAR(-1.0, s.position[0], 1e-12);
}

TEST_F(InitTrajectoryTest, DropsPastPoints)
{
  msg.header.stamp = ros::Time(9.5);  // first point at 10.5 is past at 11
  const SegmentsPerJoint<Segment> traj = updateJointTrajectory<Segment>(msg, ros::Time(11.0), options, error);
  ASSERT_EQ(2u, traj.size());
  State s;
  sampleJointTrajectory<Segment>(traj[0], 11.5, s);
  EXPECT_NEAR(2.0, s.position[0], 1e-12);  // bridged straight to the last point

  msg.header.stamp = ros::Time(5.0);  // every point is past
  EXPECT_TRUE(updateJointTrajectory<Segment>(msg, ros::Time(11.0), options, error).empty());
  EXPECT_EQ(Result::INVALID_GOAL, error.error_code);
  EXPECT_EQ("Dropping all 2 trajectory point(s), as they occur before the current time.", error.error_string);
}

TEST_F(InitTrajectoryTest, BadMessages)
{
  trajectory_msgs::JointTrajectory bad = msg;
  bad.joint_names = { "j1" };
  for (auto& p : bad.points)
    p.positions.resize(1);
  EXPECT_TRUE(updateJointTrajectory<Segment>(bad, ros::Time(1.0), options, error).empty());
  EXPECT_EQ(Result::INVALID_JOINTS, error.error_code);

  bad = msg;
  bad.joint_names[0] = "bad_name";
  error = TrajectoryError();
  EXPECT_TRUE(updateJointTrajectory<Segment>(bad, ros::Time(1.0), options, error).empty());
  EXPECT_EQ(Result::INVALID_JOINTS, error.error_code);

  bad = msg;
  bad.points[1].positions.pop_back();
  error = TrajectoryError();
  EXPECT_TRUE(updateJointTrajectory<Segment>(bad, ros::Time(1.0), options, error).empty());
  EXPECT_EQ(Result::INVALID_GOAL, error.error_code);

  bad = msg;
  bad.points[1].time_from_start = bad.points[0].time_from_start;
  error = TrajectoryError();
  EXPECT_TRUE(updateJointTrajectory<Segment>(bad, ros::Time(1.0), options, error).empty());
  EXPECT_EQ(Result::INVALID_GOAL, error.error_code);
}

TEST_F(InitTrajectoryTest, PartialJointsKeepTheirTrajectory)
{
  current = updateJointTrajectory<Segment>(msg, ros::Time(10.0), options, error);
  trajectory_msgs::JointTrajectory partial;
  partial.joint_names = { "j2" };
  partial.points.resize(1);
  partial.points[0].positions = { -1.0 };
  partial.points[0].time_from_start = ros::Duration(1.0);
  EXPECT_TRUE(updateJointTrajectory<Segment>(partial, ros::Time(10.0), options, error).empty());
  EXPECT_EQ(Result::INVALID_JOINTS, error.error_code);

  options.allow_partial_joints_goal = true;
  error = TrajectoryError();
  const SegmentsPerJoint<Segment> traj = updateJointTrajectory<Segment>(partial, ros::Time(10.0), options, error);
  ASSERT_EQ(2u, traj.size());
  State s;
  sampleJointTrajectory<Segment>(traj[0], 12.0, s);
  EXPECT_NEAR(2.0, s.position[0], 1e-12);  // j1 unchanged
  sampleJointTrajectory<Segment>(traj[1], 11.0, s);
  EXPECT_NEAR(-1.0, s.position[0], 1e-12);
}

TEST_F(InitTrajectoryTest, ContinuousJointWraps)
{
  msg.points.resize(1);
  msg.points[0].positions = { 2.0 * M_PI + 0.5, 2.0 * M_PI + 0.5 };
  const SegmentsPerJoint<Segment> traj = updateJointTrajectory<Segment>(msg, ros::Time(0.0), options, error);
  State s;
  sampleJointTrajectory<Segment>(traj[0], 1.0, s);
  EXPECT_NEAR(2.0 * M_PI + 0.5, s.position[0], 1e-9);  // j1 is not continuous
  sampleJointTrajectory<Segment>(traj[1], 1.0, s);
  EXPECT_NEAR(0.5, s.position[0], 1e-9);  // j2 takes the short way
}

TEST(HoldTrajectoryTest, StopRampAndImmediateStop)
{
  std::vector<std::string> names = { "j" };
  SegmentsPerJoint<Segment> moving(1);
  moving[0].emplace_back(0.0, state(0.0, { 1.0 }, { 0.0 }), 10.0, state(10.0, { 1.0 }, { 0.0 }));
  const SegmentsPerJoint<Segment> ramp = holdTrajectory<Segment>(&moving, { 4.0 }, 5.0, 0.4);
  State s;
  double last_pos = -1.0;
  for (double t = 5.0; t <= 5.4 + 1e-9; t += 0.01)
  {
    sampleJointTrajectory<Segment>(ramp[0], t, s);
    EXPECT_GE(s.velocity[0], -1e-12);  // decelerates without reversing
    EXPECT_GE(s.position[0], last_pos);
    last_pos = s.position[0];
  }
  sampleJointTrajectory<Segment>(ramp[0], 5.4, s);
  EXPECT_NEAR(5.0 + 0.5 * 1.0 * 0.4, s.position[0], 1e-9);  // from the desired position, not the actual one
  EXPECT_NEAR(0.0, s.velocity[0], 1e-9);

  const SegmentsPerJoint<Segment> now = holdTrajectory<Segment>(&moving, { 4.0 }, 5.0, 0.0);
  sampleJointTrajectory<Segment>(now[0], 5.0, s);
  EXPECT_DOUBLE_EQ(4.0, s.position[0]);  // at the actual position
  EXPECT_DOUBLE_EQ(0.0, s.velocity[0]);
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
