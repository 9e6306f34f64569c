#include <gtest/gtest.h>

#include <diff_drive_controller/speed_limiter.h>

using diff_drive_controller::SpeedLimiter;

TEST(SpeedLimiter, NoLimitsPassThrough)
{
  SpeedLimiter limiter;
  double v = 7.0;
  EXPECT_EQ(1.0, limiter.limit(v, 0.0, 0.0, 0.01));
  EXPECT_EQ(7.0, v);
}

TEST(SpeedLimiter, Velocity)
{
  SpeedLimiter limiter(true, false, false, -0.5, 1.0);
  double v = 2.0;
  EXPECT_DOUBLE_EQ(0.5, limiter.limit_velocity(v));
  EXPECT_EQ(1.0, v);
  v = -2.0;
  limiter.limit_velocity(v);
  EXPECT_EQ(-0.5, v);
  v = 0.0;
  EXPECT_EQ(1.0, limiter.limit_velocity(v));  // factor of a zero command
}

TEST(SpeedLimiter, Acceleration)
{
  SpeedLimiter limiter(false, true, false, 0, 0, -2.0, 1.0);
  double v = 1.0;
  limiter.limit_acceleration(v, 0.0, 0.1);  // at most +0.1 per 0.1 s
  EXPECT_DOUBLE_EQ(0.1, v);
  v = -1.0;
  limiter.limit_acceleration(v, 0.0, 0.1);
  EXPECT_DOUBLE_EQ(-0.2, v);
}

TEST(SpeedLimiter, AccelerationRampReachesTarget)
{
  SpeedLimiter limiter(true, true, false, -1.0, 1.0, -1.0, 1.0);
  double last = 0.0, before = 0.0;
  int steps = 0;
  while (last < 1.0 && steps < 1000)
  {
    double v = 5.0;
    limiter.limit(v, last, before, 0.01);
    before = last;
    last = v;
    ++steps;
  }
  EXPECT_EQ(1.0, last);
  EXPECT_NEAR(100, steps, 1);  // 1 m/s at 1 m/s^2 takes 1 s
}

TEST(SpeedLimiter, Jerk)
{
  SpeedLimiter limiter(false, false, true, 0, 0, 0, 0, -1.0, 1.0);
  double v = 1.0;
  // from rest: da limited to jerk * 2 dt^2 = 0.02 for dt 0.1
  limiter.limit_jerk(v, 0.0, 0.0, 0.1);
  EXPECT_DOUBLE_EQ(0.02, v);
}

TEST(SpeedLimiter, LimitReturnsOverallFactor)
{
  SpeedLimiter limiter(true, false, false, -1.0, 1.0);
  double v = 4.0;
  EXPECT_DOUBLE_EQ(0.25, limiter.limit(v, 0.0, 0.0, 0.01));
}
