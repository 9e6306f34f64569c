#include <gtest/gtest.h>

#include <control_toolbox/angles.h>

using namespace control_toolbox::angles;

TEST(Angles, Normalize)
{
  EXPECT_NEAR(0.0, normalize_angle(2 * M_PI), 1e-12);
  EXPECT_NEAR(M_PI, normalize_angle(-M_PI), 1e-12);
  EXPECT_NEAR(-M_PI / 2, normalize_angle(3 * M_PI / 2), 1e-12);
  EXPECT_NEAR(3 * M_PI / 2, normalize_angle_positive(-M_PI / 2), 1e-12);
}

TEST(Angles, ShortestDistance)
{
  EXPECT_NEAR(0.2, shortest_angular_distance(M_PI - 0.1, -M_PI + 0.1), 1e-12);
  EXPECT_NEAR(-0.5, shortest_angular_distance(1.0, 0.5), 1e-12);
  EXPECT_NEAR(M_PI / 2, shortest_angular_distance(0.0, 5 * M_PI / 2), 1e-12);
}

TEST(Angles, TwoPiComplement)
{
  EXPECT_NEAR(2 * M_PI - 1.0, two_pi_complement(-1.0), 1e-12);
  EXPECT_NEAR(1.0 - 2 * M_PI, two_pi_complement(1.0), 1e-12);
  EXPECT_NEAR(2 * M_PI, two_pi_complement(0.0), 1e-12);
}

TEST(Angles, WithLimitsInsideGoesDirect)
{
  double a = 0.0;
  EXPECT_TRUE(shortest_angular_distance_with_limits(0.0, 1.5, -2.0, 2.0, a));
  EXPECT_NEAR(1.5, a, 1e-12);
}

TEST(Angles, WithLimitsGoesTheLongWayRound)
{
  // from -3 to 3 the short way crosses pi, outside limits [-3.1, 3.1]: go through 0
  double a = 0.0;
  EXPECT_TRUE(shortest_angular_distance_with_limits(-3.0, 3.0, -3.1, 3.1, a));
  EXPECT_NEAR(6.0, a, 1e-12);
}

TEST(Angles, WithLimitsTargetOutside)
{
  double a = 0.0;
  EXPECT_FALSE(shortest_angular_distance_with_limits(0.0, 2.5, -1.0, 1.0, a));
  EXPECT_NEAR(2.5, a, 1e-12);  // still heads toward the target, the caller clamps it
}

TEST(Angles, WithLargeLimits)
{
  double a = 0.0;
  // limits [-4, 4] (more than 2 pi): from 3 to -3 the short way (+0.28) would end at 3.28: fine
  EXPECT_TRUE(shortest_angular_distance_with_large_limits(3.0, -3.0, -4.0, 4.0, a));
  EXPECT_NEAR(2 * M_PI - 6.0, a, 1e-12);
  // from 3.9 to -3.0: +0.28 would leave the limits, go the long way round
  EXPECT_TRUE(shortest_angular_distance_with_large_limits(3.9, -3.0 + 2 * M_PI - 2 * M_PI, -4.0, 4.0, a));
  EXPECT_GE(3.9 + a, -4.0);
  EXPECT_LE(3.9 + a, 4.0);
  EXPECT_NEAR(revolute_error(0.0, 1.5, -2.0, 2.0), 1.5, 1e-12);
  EXPECT_NEAR(revolute_error(0.0, 1.5, -10.0, 10.0), 1.5, 1e-12);
}
