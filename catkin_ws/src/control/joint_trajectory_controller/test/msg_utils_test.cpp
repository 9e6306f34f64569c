// joint_trajectory_msg_utils.h and trajectory_interface.h: message checks, point and segment look-up.
#include <vector>

#include <gtest/gtest.h>

#include <joint_trajectory_controller/joint_trajectory_msg_utils.h>
#include <trajectory_interface/quintic_spline_segment.h>
#include <trajectory_interface/trajectory_interface.h>

using namespace joint_trajectory_controller;
typedef trajectory_interface::QuinticSplineSegment<double> Segment;

static trajectory_msgs::JointTrajectory message()
{
  trajectory_msgs::JointTrajectory msg;
  msg.header.stamp = ros::Time(0.5);
  msg.joint_names = { "a" };
  for (double t : { 1.0, 2.0, 4.0 })
  {
    trajectory_msgs::JointTrajectoryPoint p;
    p.positions = { t };
    p.velocities = { 0.0 };
    p.time_from_start = ros::Duration(t);
    msg.points.push_back(p);
  }
  return msg;
}

TEST(MsgUtilsTest, StartTimeAndChecks)
{
  trajectory_msgs::JointTrajectory msg = message();
  EXPECT_EQ(ros::Time(0.5), internal::startTime(msg, ros::Time(7.0)));
  msg.header.stamp = ros::Time(0.0);
  EXPECT_EQ(ros::Time(7.0), internal::startTime(msg, ros::Time(7.0)));

  msg = message();
  EXPECT_TRUE(isValid(msg));
  msg.points[1].positions.clear();  // not given: still valid
  EXPECT_TRUE(isValid(msg));
  msg.points[1].accelerations = { 0.0, 1.0 };
  EXPECT_FALSE(isValid(msg));
  msg = message();
  msg.joint_names.push_back("b");
  EXPECT_FALSE(isValid(msg));

  msg = message();
  EXPECT_TRUE(isTimeStrictlyIncreasing(msg));
  msg.points[2].time_from_start = msg.points[1].time_from_start;
  EXPECT_FALSE(isTimeStrictlyIncreasing(msg));
}

TEST(MsgUtilsTest, FindPoint)
{
  const trajectory_msgs::JointTrajectory msg = message();
  const auto& pts = msg.points;
  EXPECT_EQ(pts.end(), findPoint(msg, ros::Time(1.0)));        // before the first point (1.5)
  EXPECT_EQ(pts.begin(), findPoint(msg, ros::Time(1.5)));      // at the first
  EXPECT_EQ(pts.begin(), findPoint(msg, ros::Time(2.0)));      // between
  EXPECT_EQ(pts.begin() + 1, findPoint(msg, ros::Time(2.5)));  // at the second
  EXPECT_EQ(pts.begin() + 2, findPoint(msg, ros::Time(9.0)));  // after the last
}

TEST(TrajectoryInterfaceTest, FindAndSample)
{
  std::vector<Segment> traj;
  Segment::State s0(1), s1(1), s2(1), s3(1);
  s0.position[0] = 2.0;
  s1.position[0] = 4.0;
  s2.position[0] = 3.0;
  s3.position[0] = 4.0;
  traj.emplace_back(1.0, s0, 2.0, s1);
  traj.emplace_back(2.0, s1, 4.0, s2);
  traj.emplace_back(5.0, s2, 6.0, s3);  // a gap between 4 and 5
  EXPECT_EQ(traj.end(), trajectory_interface::findSegment(traj.begin(), traj.end(), 0.5));
  EXPECT_EQ(traj.begin(), trajectory_interface::findSegment(traj.begin(), traj.end(), 1.0));
  EXPECT_EQ(traj.begin() + 1, trajectory_interface::findSegment(traj, 2.0));
  EXPECT_EQ(traj.begin() + 1, trajectory_interface::findSegment(traj, 4.5));  // in the gap: the previous one
  EXPECT_EQ(traj.begin() + 2, trajectory_interface::findSegment(traj, 9.0));

  Segment::State s;
  EXPECT_EQ(traj.end(), trajectory_interface::sample(traj, 0.0, s));
  EXPECT_NEAR(2.0, s.position[0], 1e-12);  // the first segment holds its start
  trajectory_interface::sample(traj, 1.5, s);
  EXPECT_NEAR(3.0, s.position[0], 1e-12);
  trajectory_interface::sample(traj, 4.5, s);
  EXPECT_NEAR(3.0, s.position[0], 1e-12);
  std::vector<Segment> empty;
  EXPECT_EQ(empty.end(), trajectory_interface::sample(empty, 1.0, s));
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

TEST(MsgUtilsTest, IsBeforePoint)
{
  trajectory_msgs::JointTrajectoryPoint point;
  point.time_from_start = ros::Duration(1.0);
  const internal::IsBeforePoint before(ros::Time(2.0));
  EXPECT_TRUE(before(ros::Time(2.5), point));
  EXPECT_FALSE(before(ros::Time(3.0), point));  // reached at 3.0: not before it
  EXPECT_FALSE(before(ros::Time(3.5), point));
}
