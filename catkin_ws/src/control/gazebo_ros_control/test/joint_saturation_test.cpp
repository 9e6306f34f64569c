// JointSaturation and BridgeModel: master-free unit tests.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <gazebo_ros_control/bridge_model.h>
#include <gazebo_ros_control/joint_saturation.h>

using gazebo_ros_control::BridgeJoint;
using gazebo_ros_control::BridgeModel;
using gazebo_ros_control::JointInterface;
using gazebo_ros_control::JointSaturation;

namespace
{
BridgeJoint joint(JointInterface iface)
{
  BridgeJoint j;
  j.name = "j";
  j.interface = iface;
  j.has_position_limits = true;
  j.lower = -1.0;
  j.upper = 2.0;
  j.has_effort_limit = true;
  j.effort = 10.0;
  j.has_velocity_limit = true;
  j.velocity = 3.0;
  return j;
}
const double NaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

TEST(JointSaturation, EffortClampedAndNoPushPastLimits)
{
  JointSaturation s(joint(JointInterface::EFFORT));
  EXPECT_DOUBLE_EQ(10.0, s.enforce(25.0, 0.0, 0.0, 0.01));
  EXPECT_DOUBLE_EQ(-10.0, s.enforce(-25.0, 0.0, 0.0, 0.01));
  EXPECT_DOUBLE_EQ(4.0, s.enforce(4.0, 0.0, 0.0, 0.01));
  EXPECT_DOUBLE_EQ(0.0, s.enforce(5.0, 2.5, 0.0, 0.01));    // past upper: no more push out
  EXPECT_DOUBLE_EQ(-5.0, s.enforce(-5.0, 2.5, 0.0, 0.01));  // but back in is fine
  EXPECT_DOUBLE_EQ(0.0, s.enforce(-5.0, 0.0, -4.0, 0.01));  // faster than the limit
  EXPECT_TRUE(std::isnan(s.enforce(NaN, 0.0, 0.0, 0.01)));
}

TEST(JointSaturation, VelocityClamped)
{
  JointSaturation s(joint(JointInterface::VELOCITY));
  EXPECT_DOUBLE_EQ(3.0, s.enforce(7.0, 0.0, 0.0, 0.01));
  EXPECT_DOUBLE_EQ(-3.0, s.enforce(-7.0, 0.0, 0.0, 0.01));
  EXPECT_DOUBLE_EQ(1.5, s.enforce(1.5, 0.0, 0.0, 0.01));
}

TEST(JointSaturation, PositionClampedAndRateLimited)
{
  JointSaturation s(joint(JointInterface::POSITION));
  // from the current position 0 at most 3 rad/s * 0.1 s
  EXPECT_NEAR(0.3, s.enforce(1.5, 0.0, 0.0, 0.1), 1e-12);
  EXPECT_NEAR(0.6, s.enforce(1.5, 0.0, 0.0, 0.1), 1e-12);
  for (int i = 0; i < 100; ++i)
    s.enforce(5.0, 0.0, 0.0, 0.1);
  EXPECT_DOUBLE_EQ(2.0, s.enforce(5.0, 0.0, 0.0, 0.1));  // upper limit
  s.reset();
  EXPECT_NEAR(-0.3, s.enforce(-5.0, 0.0, 0.0, 0.1), 1e-12);
}

TEST(JointSaturation, NoLimitsNoChange)
{
  BridgeJoint j;
  j.interface = JointInterface::POSITION;
  JointSaturation s(j);
  EXPECT_DOUBLE_EQ(100.0, s.enforce(100.0, 0.0, 0.0, 0.01));
  j.interface = JointInterface::EFFORT;
  JointSaturation e(j);
  EXPECT_DOUBLE_EQ(-1e6, e.enforce(-1e6, 0.0, 0.0, 0.01));
}

TEST(BridgeModel, StateByNameAnyOrder)
{
  BridgeJoint a = joint(JointInterface::EFFORT);
  a.name = "a";
  BridgeJoint b = joint(JointInterface::VELOCITY);
  b.name = "b";
  BridgeModel m({ a, b });
  std::string error;
  ASSERT_TRUE(m.setState({ "b", "x", "a" }, { 1.0, 2.0, 3.0 }, { 4.0, 5.0, 6.0 }, {}, &error)) << error;
  EXPECT_DOUBLE_EQ(3.0, m.position(0));
  EXPECT_DOUBLE_EQ(1.0, m.position(1));
  EXPECT_DOUBLE_EQ(6.0, m.velocity(0));
  EXPECT_DOUBLE_EQ(0.0, m.effort(1));
  ASSERT_TRUE(m.setState({ "b", "x", "a" }, { 7.0, 2.0, 8.0 }, {}, {}, &error)) << error;
  EXPECT_DOUBLE_EQ(8.0, m.position(0));
  EXPECT_FALSE(m.setState({ "b" }, { 1.0 }, {}, {}, &error));
  EXPECT_NE(std::string::npos, error.find("'a' is missing")) << error;
  EXPECT_FALSE(m.setState({ "a", "b" }, { 1.0 }, {}, {}, &error));
  EXPECT_NE(std::string::npos, error.find("shorter")) << error;
  EXPECT_DOUBLE_EQ(8.0, m.position(0));  // kept
  EXPECT_TRUE(std::isnan(m.command(0)));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
