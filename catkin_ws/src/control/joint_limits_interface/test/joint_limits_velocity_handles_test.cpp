// Limits handles (velocity saturation / soft limits) and the limits interfaces: expected values
// computed by hand in each test.
#include "handles_test_common.h"

// ---------------------------------------------------------------- VelocityJointSaturationHandle
TEST(VelocityJointSaturationHandleTest, VelocityLimit)
{
  JointData d;
  VelocityJointSaturationHandle h(d.handle(), positionVelocityLimits());
  d.cmd = 5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(2.0, d.cmd, EPS);
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-2.0, d.cmd, EPS);
  d.cmd = 1.5;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(1.5, d.cmd, EPS);
}

TEST(VelocityJointSaturationHandleTest, AccelerationLimitAroundMeasuredVelocity)
{
  JointLimits l = positionVelocityLimits();
  l.has_acceleration_limits = true;
  l.max_acceleration = 10.0;  // 1.0 rad/s per 0.1 s
  JointData d;
  d.vel = 0.5;
  VelocityJointSaturationHandle h(d.handle(), l);
  d.cmd = 5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(1.5, d.cmd, EPS);
  d.cmd = -5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-0.5, d.cmd, EPS);
  d.vel = 1.8;
  d.cmd = 5.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(2.0, d.cmd, EPS);
}

TEST(VelocityJointSaturationHandleTest, NeedsVelocityLimits)
{
  JointData d;
  EXPECT_EQ("Cannot enforce limits for joint 'wheel'. It has no velocity limits specification.",
            errorOf([&] { VelocityJointSaturationHandle(d.handle("wheel"), JointLimits()); }));
}

// ---------------------------------------------------------------- VelocityJointSoftLimitsHandle
namespace
{
/// soft [-0.5, 0.5], k_position 4.
SoftJointLimits velocitySoftLimits()
{
  SoftJointLimits s;
  s.min_position = -0.5;
  s.max_position = 0.5;
  s.k_position = 4.0;
  return s;
}
}  // namespace

TEST(VelocityJointSoftLimitsHandleTest, RangeShrinksNearSoftLimit)
{
  JointData d;
  VelocityJointSoftLimitsHandle h(d.handle(), positionVelocityLimits(), velocitySoftLimits());
  // at 0: [sat(-2), sat(2)] = ±2
  d.cmd = 3.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(2.0, d.cmd, EPS);
  // at 0.25: max = sat(-4*(-0.25)) = 1
  d.pos = 0.25;
  d.cmd = 3.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(1.0, d.cmd, EPS);
  d.cmd = -3.0;  // min = sat(-4*0.75) = -2
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-2.0, d.cmd, EPS);
  // beyond the soft limit at 0.75: max = sat(-1) = -1 → must move back
  d.pos = 0.75;
  d.cmd = 0.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(-1.0, d.cmd, EPS);
}

TEST(VelocityJointSoftLimitsHandleTest, AccelerationLimit)
{
  JointLimits l = positionVelocityLimits();
  l.has_acceleration_limits = true;
  l.max_acceleration = 10.0;
  JointData d;
  VelocityJointSoftLimitsHandle h(d.handle(), l, velocitySoftLimits());
  d.cmd = 3.0;
  h.enforceLimits(PERIOD);
  EXPECT_NEAR(1.0, d.cmd, EPS);
  d.vel = -1.5;
  d.cmd = -3.0;
  h.enforceLimits(PERIOD);  // [max(-2.5, -2), min(-0.5, 2)]
  EXPECT_NEAR(-2.0, d.cmd, EPS);
}

TEST(VelocityJointSoftLimitsHandleTest, NoLimitsPassThrough)
{
  JointData d;
  VelocityJointSoftLimitsHandle h(d.handle(), JointLimits(), SoftJointLimits());
  d.cmd = 100.0;
  h.enforceLimits(PERIOD);
  EXPECT_EQ(100.0, d.cmd);
}

// ---------------------------------------------------------------- interfaces
TEST(JointLimitsInterfaceTest, EnforcesAndResetsAllHandles)
{
  JointData a, b;
  a.pos = 0.5;
  b.pos = -0.5;
  PositionJointSaturationInterface iface;
  iface.registerHandle(PositionJointSaturationHandle(a.handle("a"), positionVelocityLimits()));
  iface.registerHandle(PositionJointSaturationHandle(b.handle("b"), positionVelocityLimits()));
  EXPECT_EQ((std::vector<std::string>{ "a", "b" }), iface.getNames());
  EXPECT_EQ("b", iface.getHandle("b").getName());

  a.cmd = 5.0;
  b.cmd = -5.0;
  iface.enforceLimits(PERIOD);
  EXPECT_NEAR(0.7, a.cmd, EPS);
  EXPECT_NEAR(-0.7, b.cmd, EPS);

  a.pos = 0.0;
  b.pos = 0.0;
  iface.reset();
  a.cmd = 5.0;
  b.cmd = -5.0;
  iface.enforceLimits(PERIOD);
  EXPECT_NEAR(0.2, a.cmd, EPS);
  EXPECT_NEAR(-0.2, b.cmd, EPS);
}

TEST(JointLimitsInterfaceTest, MissingHandleThrowsJointLimitsInterfaceException)
{
  VelocityJointSaturationInterface iface;
  const std::string msg = errorOf([&] { iface.getHandle("nope"); });
  EXPECT_EQ(0u, msg.find("Could not find resource 'nope' in '")) << msg;
}

TEST(JointLimitsInterfaceTest, AllSixInterfaces)
{
  JointData d;
  const JointLimits l = effortLimits();
  const SoftJointLimits s = effortSoftLimits();
  PositionJointSoftLimitsInterface p;
  p.registerHandle(PositionJointSoftLimitsHandle(d.handle(), l, s));
  EffortJointSaturationInterface e;
  e.registerHandle(EffortJointSaturationHandle(d.handle(), l));
  EffortJointSoftLimitsInterface es;
  es.registerHandle(EffortJointSoftLimitsHandle(d.handle(), l, s));
  VelocityJointSaturationInterface v;
  v.registerHandle(VelocityJointSaturationHandle(d.handle(), l));
  VelocityJointSoftLimitsInterface vs;
  vs.registerHandle(VelocityJointSoftLimitsHandle(d.handle(), l, s));

  d.cmd = 50.0;
  e.enforceLimits(PERIOD);
  EXPECT_NEAR(10.0, d.cmd, EPS);
  d.cmd = 50.0;
  v.enforceLimits(PERIOD);
  EXPECT_NEAR(2.0, d.cmd, EPS);
  d.cmd = 50.0;
  vs.enforceLimits(PERIOD);  // pos 0: [sat(-5), sat(5)] = ±2
  EXPECT_NEAR(2.0, d.cmd, EPS);
  d.cmd = 50.0;
  es.enforceLimits(PERIOD);
  EXPECT_NEAR(10.0, d.cmd, EPS);
  d.cmd = 50.0;
  p.enforceLimits(PERIOD);  // from 0, ±2 rad/s → 0.2
  EXPECT_NEAR(0.2, d.cmd, EPS);
  // stateless handles: reset() exists and changes nothing
  e.reset();
  es.reset();
  v.reset();
  vs.reset();
  p.reset();
  d.cmd = 50.0;
  p.enforceLimits(PERIOD);
  EXPECT_NEAR(0.2, d.cmd, EPS);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
