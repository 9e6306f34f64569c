// initJointTrajectory<Trajectory> as the original's (per-joint trajectories): dropping past points,
// combining with the current trajectory, wraparound, partial joints, goal handles, other time base.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <actionlib/server/action_server.h>
#include <joint_trajectory_controller/init_joint_trajectory.h>
#include <trajectory_interface/quintic_spline_segment.h>

using namespace joint_trajectory_controller;
using trajectory_msgs::JointTrajectoryPoint;
using std::string;
using std::vector;

typedef JointTrajectorySegment<trajectory_interface::QuinticSplineSegment<double>> Segment;
typedef vector<Segment> TrajectoryPerJoint;
typedef vector<TrajectoryPerJoint> Trajectory;

TEST(MappingTest, MappingAndPermutation)
{
  const vector<string> all = { "A", "B", "C", "D" };
  const vector<string> shuffled = { "B", "D", "A", "C" };
  EXPECT_EQ(vector<unsigned int>({ 2, 1 }), internal::mapping(vector<string>({ "C", "B" }), all));
  EXPECT_TRUE(internal::mapping(vector<string>({ "C", "X" }), all).empty());
  EXPECT_TRUE(internal::mapping(all, vector<string>({ "A" })).empty());
  EXPECT_EQ(vector<unsigned int>({ 2, 0, 3, 1 }), internal::permutation(all, shuffled));
  EXPECT_EQ(vector<unsigned int>({ 1, 3, 0, 2 }), internal::permutation(shuffled, all));
  EXPECT_TRUE(internal::permutation(all, vector<string>(3, "A")).empty());
}

class InitTrajectoryTest : public ::testing::Test
{
protected:
  InitTrajectoryTest() : points(3)
  {
    const double pos[3] = { 2.0, 4.0, 3.0 }, t[3] = { 1.0, 2.0, 4.0 };
    for (int i = 0; i < 3; ++i)
    {
      points[i].positions.assign(1, pos[i]);
      points[i].velocities.assign(1, 0.0);
      points[i].accelerations.assign(1, 0.0);
      points[i].time_from_start = ros::Duration(t[i]);
    }
    msg.header.stamp = ros::Time(0.5);
    msg.joint_names.assign(1, "foo_joint");
    msg.points = points;

    Segment::State s0, s1;
    s0.position = { 0.0 };
    s0.velocity = { 0.0 };
    s0.acceleration = { 0.0 };
    s1.position = { 1.0 };
    s1.velocity = { 1.0 };
    s1.acceleration = { 1.0 };
    curr_traj.resize(1);
    curr_traj[0].push_back(Segment(0.0, s0, 1.0, s1));
    curr_traj[0].push_back(Segment(3.0, s1, 10.0, s0));  // discarded by the tests below
  }

  ros::Time at(double t_from_stamp) const { return msg.header.stamp + ros::Duration(t_from_stamp); }

  vector<JointTrajectoryPoint> points;
  trajectory_msgs::JointTrajectory msg;
  Trajectory curr_traj;
};

TEST_F(InitTrajectoryTest, InitException)
{
  msg.points.back().positions.push_back(0.0);
  EXPECT_THROW(initJointTrajectory<Trajectory>(msg, msg.header.stamp), std::invalid_argument);
}

TEST_F(InitTrajectoryTest, InitLogic)
{
  EXPECT_TRUE(initJointTrajectory<Trajectory>(trajectory_msgs::JointTrajectory(), msg.header.stamp).empty());
  Trajectory traj = initJointTrajectory<Trajectory>(msg, at(0.0));  // before the first point: all
  ASSERT_EQ(1u, traj.size());
  EXPECT_EQ(2u, traj[0].size());
  traj = initJointTrajectory<Trajectory>(msg, at(1.0));  // at the first point: it is dropped
  ASSERT_EQ(1u, traj.size());
  EXPECT_EQ(1u, traj[0].size());
  traj = initJointTrajectory<Trajectory>(msg, at(1.5));
  ASSERT_EQ(1u, traj.size());
  EXPECT_EQ(1u, traj[0].size());
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(2.0)).empty());  // one point left: no segment
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(3.0)).empty());
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(4.0)).empty());
  string error;
  InitJointTrajectoryOptions<Trajectory> options;
  options.error_string = &error;
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(5.0), options).empty());
  EXPECT_NE(string::npos, error.find("Dropping all 3 trajectory point(s)")) << error;
}

TEST_F(InitTrajectoryTest, InitLogicCombine)
{
  InitJointTrajectoryOptions<Trajectory> options;
  options.current_trajectory = &curr_traj;
  EXPECT_TRUE(initJointTrajectory<Trajectory>(trajectory_msgs::JointTrajectory(), at(0.0), options).empty());
  // last of current + bridge + the message's segments
  EXPECT_EQ(4u, initJointTrajectory<Trajectory>(msg, ros::Time(curr_traj[0][0].startTime()), options)[0].size());
  EXPECT_EQ(4u, initJointTrajectory<Trajectory>(msg, at(0.0), options)[0].size());
  EXPECT_EQ(3u, initJointTrajectory<Trajectory>(msg, at(1.0), options)[0].size());
  EXPECT_EQ(3u, initJointTrajectory<Trajectory>(msg, at(1.5), options)[0].size());
  EXPECT_EQ(2u, initJointTrajectory<Trajectory>(msg, at(2.0), options)[0].size());
  EXPECT_EQ(2u, initJointTrajectory<Trajectory>(msg, at(3.0), options)[0].size());
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(4.0), options).empty());
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(5.0), options).empty());
}

TEST_F(InitTrajectoryTest, InitValues)
{
  const Trajectory traj = initJointTrajectory<Trajectory>(msg, at(0.0));
  ASSERT_EQ(1u, traj.size());
  ASSERT_EQ(2u, traj[0].size());
  for (unsigned int i = 0; i < 2; ++i)
  {
    const Segment& seg = traj[0][i];
    EXPECT_EQ((msg.header.stamp + points[i].time_from_start).toSec(), seg.startTime());
    EXPECT_EQ((msg.header.stamp + points[i + 1].time_from_start).toSec(), seg.endTime());
    Segment::State s;
    seg.sample(seg.startTime(), s);
    EXPECT_NEAR(points[i].positions[0], s.position[0], 1e-12);
    seg.sample(seg.endTime(), s);
    EXPECT_NEAR(points[i + 1].positions[0], s.position[0], 1e-12);
    EXPECT_FALSE(seg.getGoalHandle());
  }
}

TEST_F(InitTrajectoryTest, InitValuesCombine)
{
  InitJointTrajectoryOptions<Trajectory> options;
  options.current_trajectory = &curr_traj;
  const Trajectory traj = initJointTrajectory<Trajectory>(msg, ros::Time(0.0), options);
  ASSERT_EQ(4u, traj[0].size());
  EXPECT_EQ(curr_traj[0][0].startTime(), traj[0][0].startTime());
  EXPECT_EQ(curr_traj[0][0].endTime(), traj[0][0].endTime());
  // Bridge: from the current trajectory at the message's start to the first point.
  const Segment& bridge = traj[0][1];
  EXPECT_EQ(msg.header.stamp.toSec(), bridge.startTime());
  EXPECT_EQ(at(1.0).toSec(), bridge.endTime());
  Segment::State ref, s;
  curr_traj[0][0].sample(msg.header.stamp.toSec(), ref);
  bridge.sample(bridge.startTime(), s);
  EXPECT_NEAR(ref.position[0], s.position[0], 1e-12);
  EXPECT_NEAR(ref.velocity[0], s.velocity[0], 1e-12);
  bridge.sample(bridge.endTime(), s);
  EXPECT_NEAR(2.0, s.position[0], 1e-12);
  EXPECT_EQ(at(1.0).toSec(), traj[0][2].startTime());
  EXPECT_EQ(at(4.0).toSec(), traj[0][3].endTime());
}

TEST_F(InitTrajectoryTest, JointMapping)
{
  msg.joint_names = { "foo_joint", "bar_joint" };
  for (JointTrajectoryPoint& p : msg.points)
  {
    p.positions.push_back(-p.positions[0]);
    p.velocities.push_back(0.0);
    p.accelerations.push_back(0.0);
  }
  vector<string> joint_names = { "bar_joint", "foo_joint" };
  InitJointTrajectoryOptions<Trajectory> options;
  options.joint_names = &joint_names;
  Trajectory traj = initJointTrajectory<Trajectory>(msg, msg.header.stamp, options);
  ASSERT_EQ(2u, traj.size());
  Segment::State s;
  traj[0][0].sample(traj[0][0].startTime(), s);
  EXPECT_NEAR(-2.0, s.position[0], 1e-12);  // bar_joint first, as joint_names says
  traj[1][0].sample(traj[1][0].startTime(), s);
  EXPECT_NEAR(2.0, s.position[0], 1e-12);

  string error;
  options.error_string = &error;
  joint_names = { "foo_joint" };  // size mismatch
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, msg.header.stamp, options).empty());
  EXPECT_NE(string::npos, error.find("does not contain the expected joints"));
  joint_names = { "foo_joint", "baz_joint" };  // value mismatch
  error.clear();
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, msg.header.stamp, options).empty());
  EXPECT_NE(string::npos, error.find("does not contain the expected joints"));
}

TEST_F(InitTrajectoryTest, PartialJoints)
{
  // The controller has foo_joint and bar_joint; the message moves bar_joint only.
  vector<string> joint_names = { "foo_joint", "bar_joint" };
  Trajectory current(2, curr_traj[0]);
  msg.joint_names = { "bar_joint" };
  InitJointTrajectoryOptions<Trajectory> options;
  options.current_trajectory = &current;
  options.joint_names = &joint_names;
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(0.0), options).empty());  // not allowed by default

  options.allow_partial_joints_goal = true;
  actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> gh;
  InitJointTrajectoryOptions<Trajectory>::RealtimeGoalHandlePtr rt_goal(
      new InitJointTrajectoryOptions<Trajectory>::RealtimeGoalHandle(gh));
  options.rt_goal_handle = rt_goal;
  const Trajectory traj = initJointTrajectory<Trajectory>(msg, ros::Time(0.0), options);
  ASSERT_EQ(2u, traj.size());
  ASSERT_EQ(2u, traj[0].size());  // foo_joint keeps its trajectory...
  EXPECT_EQ(current[0][1].endTime(), traj[0][1].endTime());
  EXPECT_EQ(rt_goal, traj[0][0].getGoalHandle());  // ...which now belongs to the new goal
  EXPECT_EQ(rt_goal, traj[0][1].getGoalHandle());
  ASSERT_EQ(4u, traj[1].size());
  EXPECT_EQ(at(4.0).toSec(), traj[1][3].endTime());
}

TEST_F(InitTrajectoryTest, WrappingSpec)
{
  const double wrap = 4.0 * M_PI;
  for (JointTrajectoryPoint& p : msg.points)
    p.positions[0] += wrap;
  vector<bool> angle_wraparound(1, true);
  InitJointTrajectoryOptions<Trajectory> options;
  options.current_trajectory = &curr_traj;
  options.angle_wraparound = &angle_wraparound;
  Trajectory traj = initJointTrajectory<Trajectory>(msg, ros::Time(0.0), options);
  ASSERT_EQ(4u, traj[0].size());
  Segment::State s;
  traj[0][1].sample(traj[0][1].endTime(), s);
  EXPECT_NEAR(msg.points[0].positions[0] - wrap, s.position[0], 1e-9);
  for (unsigned int k = 2; k < 4; ++k)
  {
    traj[0][k].sample(traj[0][k].endTime(), s);
    EXPECT_NEAR(msg.points[k - 1].positions[0] - wrap, s.position[0], 1e-9);
  }
  // Without a current trajectory the specification is ignored.
  InitJointTrajectoryOptions<Trajectory> no_current;
  no_current.angle_wraparound = &angle_wraparound;
  traj = initJointTrajectory<Trajectory>(msg, ros::Time(0.0), no_current);
  ASSERT_EQ(2u, traj[0].size());
  traj[0][0].sample(traj[0][0].startTime(), s);
  EXPECT_NEAR(msg.points[0].positions[0], s.position[0], 1e-9);
  // Wrong size: empty result.
  angle_wraparound.assign(2, true);
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, ros::Time(0.0), options).empty());
}

TEST_F(InitTrajectoryTest, GoalHandleTest)
{
  actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> gh;
  Segment::RealtimeGoalHandlePtr rt_goal(new Segment::RealtimeGoalHandle(gh));
  InitJointTrajectoryOptions<Trajectory> options;
  options.current_trajectory = &curr_traj;
  options.rt_goal_handle = rt_goal;
  const Trajectory traj = initJointTrajectory<Trajectory>(msg, ros::Time(curr_traj[0][0].startTime()), options);
  ASSERT_EQ(4u, traj[0].size());
  // The kept segment of the current trajectory keeps its (null) goal handle; the new ones carry the goal.
  EXPECT_FALSE(traj[0][0].getGoalHandle());
  for (unsigned int i = 1; i < traj[0].size(); ++i)
    EXPECT_EQ(rt_goal, traj[0][i].getGoalHandle()) << i;
}

TEST_F(InitTrajectoryTest, DefaultTolerancesWithGoal)
{
  SegmentTolerances<double> defaults(1);
  defaults.state_tolerance[0].position = 0.3;
  defaults.goal_time_tolerance = 0.7;
  InitJointTrajectoryOptions<Trajectory> options;
  options.default_tolerances = &defaults;
  Trajectory traj = initJointTrajectory<Trajectory>(msg, at(0.0), options);
  EXPECT_EQ(0.0, traj[0][0].getTolerances().state_tolerance.position);  // no goal: not applied
  actionlib::ServerGoalHandle<control_msgs::FollowJointTrajectoryAction> gh;
  options.rt_goal_handle.reset(new Segment::RealtimeGoalHandle(gh));
  traj = initJointTrajectory<Trajectory>(msg, at(0.0), options);
  EXPECT_EQ(0.3, traj[0][0].getTolerances().state_tolerance.position);
  EXPECT_EQ(0.7, traj[0][1].getTolerances().goal_time_tolerance);
}

TEST_F(InitTrajectoryTest, OtherTimeBase)
{
  InitJointTrajectoryOptions<Trajectory> options;
  const ros::Duration offset(1.0);
  ros::Time other_time_base = msg.header.stamp + offset;
  options.current_trajectory = &curr_traj;
  options.other_time_base = &other_time_base;
  const Trajectory traj = initJointTrajectory<Trajectory>(msg, msg.header.stamp, options);
  ASSERT_EQ(4u, traj[0].size());
  EXPECT_EQ(curr_traj[0][0].startTime(), traj[0][0].startTime());  // no offset on the current part
  EXPECT_EQ(msg.header.stamp.toSec() + 1.0, traj[0][1].startTime());
  EXPECT_EQ(at(1.0).toSec() + 1.0, traj[0][1].endTime());
  EXPECT_EQ(at(4.0).toSec() + 1.0, traj[0][3].endTime());
}

TEST_F(InitTrajectoryTest, NotStrictlyIncreasing)
{
  msg.points[1].time_from_start = msg.points[0].time_from_start;
  string error;
  InitJointTrajectoryOptions<Trajectory> options;
  options.error_string = &error;
  EXPECT_TRUE(initJointTrajectory<Trajectory>(msg, at(0.0), options).empty());
  EXPECT_NE(string::npos, error.find("not strictly increasing"));
}

TEST(FindPointTest, LastPointReachedAtOrBefore)
{
  trajectory_msgs::JointTrajectory msg;
  msg.header.stamp = ros::Time(1.0);
  msg.points.resize(3);
  for (int i = 0; i < 3; ++i)
    msg.points[i].time_from_start = ros::Duration(i + 1.0);
  EXPECT_EQ(msg.points.end(), findPoint(msg, ros::Time(1.5)));
  EXPECT_EQ(msg.points.begin(), findPoint(msg, ros::Time(2.0)));
  EXPECT_EQ(msg.points.begin() + 1, findPoint(msg, ros::Time(3.5)));
  EXPECT_EQ(msg.points.begin() + 2, findPoint(msg, ros::Time(9.0)));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
