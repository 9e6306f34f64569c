// Maths of control_toolbox::Pid, without a ROS master (no init(NodeHandle)).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <control_toolbox/pid.h>

using control_toolbox::Pid;

namespace
{
const ros::Duration ONE_SECOND(1.0);
}

TEST(Pid, ProportionalOnly)
{
  Pid pid(2.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(-1.0, pid.computeCommand(-0.5, ONE_SECOND));
  EXPECT_DOUBLE_EQ(3.0, pid.computeCommand(1.5, ros::Duration(0.01)));
  EXPECT_DOUBLE_EQ(3.0, pid.getCurrentCmd());
}

TEST(Pid, IntegralAccumulatesAndIsClamped)
{
  Pid pid(0.0, 1.0, 0.0, 1.0, -1.0);
  EXPECT_DOUBLE_EQ(-0.5, pid.computeCommand(-0.5, ONE_SECOND));
  EXPECT_DOUBLE_EQ(-1.0, pid.computeCommand(-0.5, ONE_SECOND));
  EXPECT_DOUBLE_EQ(-1.0, pid.computeCommand(-0.5, ONE_SECOND));  // clamped at i_min
  double pe, ie, de;
  pid.getCurrentPIDErrors(&pe, &ie, &de);
  EXPECT_DOUBLE_EQ(-1.5, ie);  // without antiwindup the integral itself keeps growing
  // it takes the error just as long to unwind
  EXPECT_DOUBLE_EQ(-1.0, pid.computeCommand(0.5, ONE_SECOND));
  EXPECT_DOUBLE_EQ(-0.5, pid.computeCommand(0.5, ONE_SECOND));
}

TEST(Pid, ZeroClampMeansNoIntegralTerm)
{
  // upstream behaviour: i_clamp defaults to 0, which clamps the i term to 0
  Pid pid(0.0, 5.0, 0.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, ONE_SECOND));
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, ONE_SECOND));
}

TEST(Pid, AntiwindupBoundsTheIntegral)
{
  Pid pid(0.0, 2.0, 0.0, 1.0, -1.0, true);
  EXPECT_DOUBLE_EQ(1.0, pid.computeCommand(1.0, ONE_SECOND));  // i_error 1 -> bounded 0.5
  EXPECT_DOUBLE_EQ(1.0, pid.computeCommand(1.0, ONE_SECOND));
  double pe, ie, de;
  pid.getCurrentPIDErrors(&pe, &ie, &de);
  EXPECT_DOUBLE_EQ(0.5, ie);
  // unwinds at once: 0.5 - 0.25 = 0.25 -> i term 0.5
  EXPECT_DOUBLE_EQ(0.5, pid.computeCommand(-0.25, ONE_SECOND));
}

TEST(Pid, AntiwindupWithNegativeIGain)
{
  Pid pid(0.0, -2.0, 0.0, 1.0, -1.0, true);
  EXPECT_DOUBLE_EQ(-1.0, pid.computeCommand(1.0, ONE_SECOND));  // bounds [-0.5, 0.5]
  EXPECT_DOUBLE_EQ(-1.0, pid.computeCommand(1.0, ONE_SECOND));
}

TEST(Pid, DerivativeByFiniteDifference)
{
  Pid pid(0.0, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(1.0, pid.computeCommand(1.0, ONE_SECOND));  // (1 - 0) / 1
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, ONE_SECOND));
  EXPECT_DOUBLE_EQ(-20.0, pid.computeCommand(0.8, ros::Duration(0.01)));
}

TEST(Pid, ExplicitErrorDot)
{
  Pid pid(1.0, 0.0, 3.0);
  EXPECT_DOUBLE_EQ(1.0 + 3.0 * -2.0, pid.computeCommand(1.0, -2.0, ros::Duration(0.1)));
}

TEST(Pid, ZeroDtReturnsZero)
{
  Pid pid(1.0, 1.0, 1.0, 10.0, -10.0);
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, ros::Duration(0.0)));
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, 1.0, ros::Duration(0.0)));
  double pe, ie, de;
  pid.getCurrentPIDErrors(&pe, &ie, &de);
  EXPECT_DOUBLE_EQ(0.0, ie);
}

TEST(Pid, NanOrInfInputReturnsZeroAndKeepsState)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Pid pid(1.0, 1.0, 0.0, 10.0, -10.0);
  EXPECT_DOUBLE_EQ(2.0, pid.computeCommand(1.0, ONE_SECOND));
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(nan, ONE_SECOND));
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(inf, ONE_SECOND));
  EXPECT_DOUBLE_EQ(0.0, pid.computeCommand(1.0, nan, ONE_SECOND));
  double pe, ie, de;
  pid.getCurrentPIDErrors(&pe, &ie, &de);
  EXPECT_DOUBLE_EQ(1.0, ie);  // the integral did not take the bad samples
  EXPECT_FALSE(std::isnan(pid.computeCommand(1.0, ONE_SECOND)));
}

TEST(Pid, UpdatePidIsNegated)
{
  Pid pid(2.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(-2.0, pid.updatePid(1.0, ONE_SECOND));
}

TEST(Pid, GainsRoundTripAndReset)
{
  Pid pid;
  pid.setGains(1.0, 2.0, 3.0, 4.0, -5.0, true);
  double p, i, d, i_max, i_min;
  bool antiwindup = false;
  pid.getGains(p, i, d, i_max, i_min, antiwindup);
  EXPECT_EQ(1.0, p);
  EXPECT_EQ(2.0, i);
  EXPECT_EQ(3.0, d);
  EXPECT_EQ(4.0, i_max);
  EXPECT_EQ(-5.0, i_min);
  EXPECT_TRUE(antiwindup);
  const Pid::Gains g = pid.getGains();
  EXPECT_EQ(3.0, g.d_gain_);

  pid.computeCommand(1.0, ONE_SECOND);
  EXPECT_NE(0.0, pid.getCurrentCmd());
  pid.reset();
  double pe, ie, de;
  pid.getCurrentPIDErrors(&pe, &ie, &de);
  EXPECT_EQ(0.0, pe);
  EXPECT_EQ(0.0, ie);
  EXPECT_EQ(0.0, de);
  EXPECT_EQ(0.0, pid.getCurrentCmd());
}

TEST(Pid, CopyKeepsGainsButNotState)
{
  Pid a(1.0, 1.0, 0.0, 10.0, -10.0);
  a.computeCommand(1.0, ONE_SECOND);
  Pid b(a);
  EXPECT_EQ(1.0, b.getGains().i_gain_);
  double pe, ie, de;
  b.getCurrentPIDErrors(&pe, &ie, &de);
  EXPECT_EQ(0.0, ie);
  std::vector<Pid> many(3, a);  // group controllers keep Pids in vectors
  EXPECT_EQ(10.0, many[2].getGains().i_max_);
}
