// Limits handles (position and effort saturation / soft limits): expected values computed by
// hand in each test.
#include "handles_test_common.h"

TEST(JointLimitsStructsTest, DefaultsAreOff)
{
  JointLimits l;
  EXPECT_FALSE(l.has_position_limits || l.has_velocity_limits || l.has_acceleration_limits || l.has_jerk_limits ||
               l.has_effort_limits || l.angle_wraparound);
  EXPECT_EQ(0.0, l.min_position + l.max_position + l.max_velocity + l.max_acceleration + l.max_jerk + l.max_effort);
  SoftJointLimits s;
  EXPECT_EQ(0.0, s.min_position + s.max_position + s.k_position + s.k_velocity);
}

// ---------------------------------------------------------------- PositionJointSaturationHandle
TEST(PositionJointSaturationHandleTest, VelocityLimitRelativeToPreviousCommand)
{
  JointData d;
  d.pos = 0.5;
  PositionJointSaturationHandle h(d.handle(), positionVelocityLimits());
  EXPECT_EQ("joint", h.getName());
  // max step = 2.0 rad/s * 0.1 s = 0.2, starting from the measured 0.5
  d.cmd = 2.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.7, d.cmd, EPS);
  // the previous command (0.7) is the reference, not the measured position (still 0.5)
  d.cmd = 2.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.9, d.cmd, EPS);
  d.cmd = 2.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(1.0, d.cmd, EPS);  // hard limit
  // inside the allowed step: unchanged
  d.cmd = 0.95;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.95, d.cmd, EPS);
}

TEST(PositionJointSaturationHandleTest, ResetRestartsFromMeasuredPosition)
{
  JointData d;
  d.pos = 0.5;
  PositionJointSaturationHandle h(d.handle(), positionVelocityLimits());
  d.cmd = 2.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.7, d.cmd, EPS);
  d.pos = 0.0;
  h.reset();
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-0.2, d.cmd, EPS);
}

TEST(PositionJointSaturationHandleTest, PositionOnlyAndNoLimits)
{
  JointData d;
  JointLimits l = positionVelocityLimits();
  l.has_velocity_limits = false;
  PositionJointSaturationHandle h(d.handle(), l);
  d.cmd = 5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(1.0, d.cmd, EPS);
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-1.0, d.cmd, EPS);

  JointData free_joint;
  PositionJointSaturationHandle unlimited(free_joint.handle(), JointLimits());
  free_joint.cmd = 1e6;
  unlimited.enforceLimits(PERIOD);
  EXPECT_EQ(1e6, free_joint.cmd);
}

// ---------------------------------------------------------------- PositionJointSoftLimitsHandle
namespace
{
/// pos [-1, 1], vel 1; soft [-0.8, 0.8], k_position 10.
struct SoftPositionFixture
{
  JointLimits limits;
  SoftJointLimits soft;
  SoftPositionFixture()
  {
    limits = positionVelocityLimits();
    limits.max_velocity = 1.0;
    soft.min_position = -0.8;
    soft.max_position = 0.8;
    soft.k_position = 10.0;
    soft.k_velocity = 123.0;  // unused by the position handle
  }
};
}  // namespace

TEST(PositionJointSoftLimitsHandleTest, FarFromSoftLimitsOnlyVelocity)
{
  SoftPositionFixture f;
  JointData d;
  PositionJointSoftLimitsHandle h(d.handle(), f.limits, f.soft);
  // at 0: bounds sat(-10*0.8)=-1 .. sat(10*0.8)=1 → ±1 * 0.1 s
  d.cmd = 0.5;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.1, d.cmd, EPS);
  d.cmd = -0.5;
  h.enforceLimits(PERIOD);  // from 0.1: [0.0, 0.2]
  EXPECT_NEAR(0.0, d.cmd, EPS);
}

TEST(PositionJointSoftLimitsHandleTest, NearAndBeyondSoftLimit)
{
  SoftPositionFixture f;
  JointData d;
  d.pos = 0.75;
  PositionJointSoftLimitsHandle h(d.handle(), f.limits, f.soft);
  // v_max = sat(-10*(0.75-0.8)) = 0.5 → high = 0.75 + 0.05 = 0.8
  d.cmd = 2.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.8, d.cmd, EPS);
  // at the soft limit v_max = 0: no further
  d.cmd = 2.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.8, d.cmd, EPS);
  // beyond it (0.9): v_max = sat(-10*0.1) = -1, v_min = -1 → the command must go back to 0.8
  h.reset();
  d.pos = 0.9;
  d.cmd = 0.9;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.8, d.cmd, EPS);
}

TEST(PositionJointSoftLimitsHandleTest, HardLimitsWinOverSoftLimitsBeyondThem)
{
  SoftPositionFixture f;
  f.soft.max_position = 2.0;
  JointData d;
  d.pos = 0.95;
  PositionJointSoftLimitsHandle h(d.handle(), f.limits, f.soft);
  // v_max = sat(-10*(0.95-2)) = 1 → 1.05, but hard max 1.0
  d.cmd = 5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(1.0, d.cmd, EPS);
}

TEST(PositionJointSoftLimitsHandleTest, ContinuousJointOnlyVelocity)
{
  SoftPositionFixture f;
  f.limits.has_position_limits = false;
  JointData d;
  d.pos = 10.0;
  PositionJointSoftLimitsHandle h(d.handle(), f.limits, f.soft);
  d.cmd = 20.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(10.1, d.cmd, EPS);
}

TEST(PositionJointSoftLimitsHandleTest, NeedsVelocityLimits)
{
  JointData d;
  EXPECT_EQ("Cannot enforce limits for joint 'wrist'. It has no velocity limits specification.",
            errorOf([&] { PositionJointSoftLimitsHandle(d.handle("wrist"), JointLimits(), SoftJointLimits()); }));
}

// ---------------------------------------------------------------- EffortJointSaturationHandle
TEST(EffortJointSaturationHandleTest, ClampsToMaxEffort)
{
  JointData d;
  EffortJointSaturationHandle h(d.handle(), effortLimits());
  d.cmd = 20.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(10.0, d.cmd, EPS);
  d.cmd = -20.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-10.0, d.cmd, EPS);
  d.cmd = 3.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(3.0, d.cmd, EPS);
}

TEST(EffortJointSaturationHandleTest, NoEffortFurtherOutOfPositionLimits)
{
  JointData d;
  EffortJointSaturationHandle h(d.handle(), effortLimits());
  d.pos = 1.5;
  d.cmd = 5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.0, d.cmd, EPS);
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-5.0, d.cmd, EPS);
  d.pos = -1.5;
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.0, d.cmd, EPS);
  d.cmd = 15.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(10.0, d.cmd, EPS);
}

TEST(EffortJointSaturationHandleTest, NoEffortFurtherBeyondVelocityLimit)
{
  JointData d;
  EffortJointSaturationHandle h(d.handle(), effortLimits());
  d.vel = 3.0;
  d.cmd = 5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.0, d.cmd, EPS);
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-5.0, d.cmd, EPS);
  d.vel = -3.0;
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.0, d.cmd, EPS);
}

TEST(EffortJointSaturationHandleTest, NeedsVelocityAndEffortLimits)
{
  JointData d;
  JointLimits no_effort = positionVelocityLimits();
  EXPECT_EQ("Cannot enforce limits for joint 'joint'. It has no efforts limits specification.",
            errorOf([&] { EffortJointSaturationHandle(d.handle(), no_effort); }));
  JointLimits no_velocity = effortLimits();
  no_velocity.has_velocity_limits = false;
  EXPECT_EQ("Cannot enforce limits for joint 'joint'. It has no velocity limits specification.",
            errorOf([&] { EffortJointSaturationHandle(d.handle(), no_velocity); }));
}

// ---------------------------------------------------------------- EffortJointSoftLimitsHandle
TEST(EffortJointSoftLimitsHandleTest, FarFromLimits)
{
  JointData d;
  EffortJointSoftLimitsHandle h(d.handle(), effortLimits(), effortSoftLimits());
  // v range ±2 (saturated from ∓5); effort range sat(-5*(0∓2)) = ±10
  d.cmd = 20.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(10.0, d.cmd, EPS);
  d.cmd = -7.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-7.0, d.cmd, EPS);
}

TEST(EffortJointSoftLimitsHandleTest, BeyondSoftLimitPushesBack)
{
  JointData d;
  d.pos = 0.6;
  EffortJointSoftLimitsHandle h(d.handle(), effortLimits(), effortSoftLimits());
  // v_max = sat(-10*0.1) = -1, v_min = sat(-10*1.1) = -2
  // at rest: effort in [sat(-5*(0+2)), sat(-5*(0+1))] = [-10, -5]
  d.cmd = 3.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-5.0, d.cmd, EPS);
  // moving back at -1: effort in [sat(-5*(-1+2)), sat(-5*(-1+1))] = [-5, 0]
  d.vel = -1.0;
  d.cmd = 3.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(0.0, d.cmd, EPS);
  d.cmd = -8.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-5.0, d.cmd, EPS);
}

TEST(EffortJointSoftLimitsHandleTest, ContinuousJoint)
{
  JointLimits l = effortLimits();
  l.has_position_limits = false;
  JointData d;
  d.pos = 100.0;  // ignored
  d.vel = 1.0;
  EffortJointSoftLimitsHandle h(d.handle(), l, effortSoftLimits());
  // v range ±2; effort in [sat(-5*(1+2)), sat(-5*(1-2))] = [-10, 5]
  d.cmd = 8.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(5.0, d.cmd, EPS);
}

TEST(EffortJointSoftLimitsHandleTest, NeedsVelocityAndEffortLimits)
{
  JointData d;
  EXPECT_EQ("Cannot enforce limits for joint 'joint'. It has no effort limits specification.",
            errorOf([&] { EffortJointSoftLimitsHandle(d.handle(), positionVelocityLimits(), effortSoftLimits()); }));
  EXPECT_EQ("Cannot enforce limits for joint 'joint'. It has no velocity limits specification.",
            errorOf([&] { EffortJointSoftLimitsHandle(d.handle(), JointLimits(), effortSoftLimits()); }));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
