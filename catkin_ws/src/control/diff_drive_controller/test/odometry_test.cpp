// diff_drive_controller::Odometry without ROS: straight line, turn in place, arcs (exact vs.
// closed form), velocity rolling window, open loop, tiny dt.
#include <gtest/gtest.h>

#include <cmath>

#include <diff_drive_controller/odometry.h>
#include <diff_drive_controller/rolling_mean_accumulator.h>

using diff_drive_controller::Odometry;

namespace
{
const double SEPARATION = 0.5;  // [m]
const double RADIUS = 0.1;      // [m]
const double DT = 0.01;         // [s]
const double EPS = 1e-9;

/// Drive with constant wheel speeds [rad/s] for `steps` steps; returns the end time.
ros::Time drive(Odometry& odom, double& left, double& right, double wl, double wr, int steps, ros::Time t)
{
  for (int i = 0; i < steps; ++i)
  {
    left += wl * DT;
    right += wr * DT;
    t += ros::Duration(DT);
    odom.update(left, right, t);
  }
  return t;
}
}  // namespace

TEST(Odometry, StartsAtOrigin)
{
  Odometry odom;
  EXPECT_EQ(0.0, odom.getX());
  EXPECT_EQ(0.0, odom.getY());
  EXPECT_EQ(0.0, odom.getHeading());
  EXPECT_EQ(0.0, odom.getLinear());
  EXPECT_EQ(0.0, odom.getAngular());
}

TEST(Odometry, StraightLine)
{
  Odometry odom;
  odom.setWheelParams(SEPARATION, RADIUS, RADIUS);
  ros::Time t(100.0);
  odom.init(t);
  double left = 0.0, right = 0.0;
  drive(odom, left, right, 10.0, 10.0, 200, t);  // 1 m/s for 2 s
  EXPECT_NEAR(2.0, odom.getX(), EPS);
  EXPECT_NEAR(0.0, odom.getY(), EPS);
  EXPECT_NEAR(0.0, odom.getHeading(), EPS);
  EXPECT_NEAR(1.0, odom.getLinear(), 1e-6);
  EXPECT_NEAR(0.0, odom.getAngular(), 1e-6);
}

TEST(Odometry, TurnInPlace)
{
  Odometry odom;
  odom.setWheelParams(SEPARATION, RADIUS, RADIUS);
  ros::Time t(1.0);
  odom.init(t);
  double left = 0.0, right = 0.0;
  // wheel speed 2.5 rad/s -> 0.25 m/s each way -> omega = 0.5 / 0.5 = 1 rad/s
  drive(odom, left, right, -2.5, 2.5, 100, t);
  EXPECT_NEAR(1.0, odom.getHeading(), 1e-9);
  EXPECT_NEAR(0.0, odom.getX(), 1e-9);
  EXPECT_NEAR(0.0, odom.getY(), 1e-9);
  EXPECT_NEAR(1.0, odom.getAngular(), 1e-6);
}

TEST(Odometry, ArcMatchesClosedForm)
{
  Odometry odom;
  odom.setWheelParams(SEPARATION, RADIUS, RADIUS);
  ros::Time t(1.0);
  odom.init(t);
  double left = 0.0, right = 0.0;
  // v = 0.5 m/s, omega = 0.5 rad/s -> radius 1 m; half a circle after pi seconds
  const double v = 0.5, w = 0.5;
  const double wl = (v - w * SEPARATION / 2) / RADIUS, wr = (v + w * SEPARATION / 2) / RADIUS;
  const int steps = 300;
  drive(odom, left, right, wl, wr, steps, t);
  const double T = steps * DT;
  EXPECT_NEAR(std::sin(w * T) / w * v, odom.getX(), 1e-9);
  EXPECT_NEAR((1 - std::cos(w * T)) / w * v, odom.getY(), 1e-9);
  EXPECT_NEAR(w * T, odom.getHeading(), 1e-9);
}

TEST(Odometry, DifferentWheelRadii)
{
  Odometry odom;
  odom.setWheelParams(SEPARATION, 0.1, 0.2);
  ros::Time t(1.0);
  odom.init(t);
  double left = 0.0, right = 0.0;
  drive(odom, left, right, 10.0, 5.0, 100, t);  // both 1 m/s
  EXPECT_NEAR(1.0, odom.getX(), 1e-9);
  EXPECT_NEAR(0.0, odom.getHeading(), 1e-9);
}

TEST(Odometry, RollingWindowSmoothsVelocity)
{
  Odometry odom(4);
  odom.setWheelParams(SEPARATION, RADIUS, RADIUS);
  ros::Time t(1.0);
  odom.init(t);
  double left = 0.0, right = 0.0;
  t = drive(odom, left, right, 10.0, 10.0, 10, t);  // 1 m/s
  EXPECT_NEAR(1.0, odom.getLinear(), 1e-6);
  t = drive(odom, left, right, 0.0, 0.0, 1, t);  // stop: mean of (1,1,1,0)
  EXPECT_NEAR(0.75, odom.getLinear(), 1e-6);
  t = drive(odom, left, right, 0.0, 0.0, 3, t);  // the window has forgotten the motion
  EXPECT_NEAR(0.0, odom.getLinear(), 1e-9);
}

TEST(Odometry, InitResetsVelocityNotPose)
{
  Odometry odom(10);
  odom.setWheelParams(SEPARATION, RADIUS, RADIUS);
  ros::Time t(1.0);
  odom.init(t);
  double left = 0.0, right = 0.0;
  t = drive(odom, left, right, 10.0, 10.0, 10, t);
  const double x = odom.getX();
  odom.init(t);
  EXPECT_EQ(x, odom.getX());
  t = drive(odom, left, right, 0.0, 0.0, 1, t);
  EXPECT_NEAR(0.0, odom.getLinear(), 1e-9);  // no old samples in the window any more
}

TEST(Odometry, TinyIntervalIntegratesButDoesNotEstimate)
{
  Odometry odom;
  odom.setWheelParams(SEPARATION, RADIUS, RADIUS);
  ros::Time t(1.0);
  odom.init(t);
  EXPECT_FALSE(odom.update(1.0, 1.0, t + ros::Duration(0.00005)));
  EXPECT_NEAR(0.1, odom.getX(), 1e-12);
  EXPECT_EQ(0.0, odom.getLinear());
}

TEST(Odometry, OpenLoop)
{
  Odometry odom;
  odom.setWheelParams(SEPARATION, RADIUS, RADIUS);
  ros::Time t(1.0);
  odom.init(t);
  for (int i = 1; i <= 100; ++i)
    odom.updateOpenLoop(2.0, 0.0, t + ros::Duration(i * DT));
  EXPECT_NEAR(2.0, odom.getX(), 1e-9);
  EXPECT_EQ(2.0, odom.getLinear());
  for (int i = 101; i <= 200; ++i)
    odom.updateOpenLoop(0.0, M_PI / 2, t + ros::Duration(i * DT));
  EXPECT_NEAR(M_PI / 2, odom.getHeading(), 1e-9);
  EXPECT_NEAR(2.0, odom.getX(), 1e-9);
}

TEST(RollingMeanAccumulator, MeanOfLastN)
{
  diff_drive_controller::RollingMeanAccumulator acc(3);
  EXPECT_EQ(0.0, acc.getRollingMean());
  acc.accumulate(3.0);
  EXPECT_EQ(3.0, acc.getRollingMean());
  acc.accumulate(6.0);
  EXPECT_EQ(4.5, acc.getRollingMean());
  acc.accumulate(9.0);
  acc.accumulate(12.0);
  EXPECT_EQ(9.0, acc.getRollingMean());
  EXPECT_EQ(3u, acc.size());
}
