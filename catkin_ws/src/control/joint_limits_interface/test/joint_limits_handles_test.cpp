// Limits handles and interfaces: expected values computed by hand in each test.
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <joint_limits_interface/joint_limits_interface.h>

using namespace joint_limits_interface;

namespace
{
const double EPS = 1e-12;

/// One joint's raw data, as a RobotHW would hold it.
struct JointData
{
  double pos = 0.0;
  double vel = 0.0;
  double eff = 0.0;
  double cmd = 0.0;

  hardware_interface::JointHandle handle(const std::string& name = "joint")
  {
    return hardware_interface::JointHandle(hardware_interface::JointStateHandle(name, &pos, &vel, &eff), &cmd);
  }
};

std::string errorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const JointLimitsInterfaceException& e)
  {
    return e.what();
  }
  return "";
}

/// pos [-1, 1], vel 2, no other limits.
JointLimits positionVelocityLimits()
{
  JointLimits l;
  l.has_position_limits = true;
  l.min_position = -1.0;
  l.max_position = 1.0;
  l.has_velocity_limits = true;
  l.max_velocity = 2.0;
  return l;
}

const ros::Duration PERIOD(0.1);
}  // namespace

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
namespace
{
/// pos [-1, 1], vel 2, effort 10.
JointLimits effortLimits()
{
  JointLimits l = positionVelocityLimits();
  l.has_effort_limits = true;
  l.max_effort = 10.0;
  return l;
}
}  // namespace

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
namespace
{
/// effortLimits(); soft [-0.5, 0.5], k_position 10, k_velocity 5.
SoftJointLimits effortSoftLimits()
{
  SoftJointLimits s;
  s.min_position = -0.5;
  s.max_position = 0.5;
  s.k_position = 10.0;
  s.k_velocity = 5.0;
  return s;
}
}  // namespace

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
