// Loading JointLimits / SoftJointLimits from URDF joints (no ROS master needed).
#include <string>

#include <gtest/gtest.h>
#include <urdf/model.h>

#include <joint_limits_interface/joint_limits_urdf.h>

using namespace joint_limits_interface;

namespace
{
const char* const URDF = R"(<?xml version="1.0"?>
<robot name="limits_bot">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/><link name="l5"/>
  <joint name="revolute_soft" type="revolute">
    <parent link="base"/><child link="l1"/>
    <limit lower="-1.5" upper="2.5" velocity="3.0" effort="40.0"/>
    <safety_controller soft_lower_limit="-1.0" soft_upper_limit="2.0" k_position="10.0" k_velocity="0.5"/>
  </joint>
  <joint name="continuous" type="continuous">
    <parent link="base"/><child link="l2"/>
    <limit velocity="8.0" effort="2.0"/>
  </joint>
  <joint name="prismatic" type="prismatic">
    <parent link="base"/><child link="l3"/>
    <limit lower="0.0" upper="0.3" velocity="0.1" effort="100.0"/>
  </joint>
  <joint name="continuous_no_limit" type="continuous">
    <parent link="base"/><child link="l4"/>
  </joint>
  <joint name="fixed" type="fixed">
    <parent link="base"/><child link="l5"/>
  </joint>
</robot>)";

class JointLimitsUrdfTest : public ::testing::Test
{
protected:
  void SetUp() override { ASSERT_TRUE(model_.initString(URDF)) << "test URDF does not parse"; }
  urdf::JointConstSharedPtr joint(const std::string& name)
  {
    urdf::JointConstSharedPtr j = model_.getJoint(name);
    EXPECT_TRUE(j != nullptr) << "no joint " << name;
    return j;
  }
  urdf::Model model_;
};
}  // namespace

TEST_F(JointLimitsUrdfTest, RevoluteJoint)
{
  JointLimits l;
  l.has_acceleration_limits = true;  // URDF has none: cleared
  l.max_acceleration = 7.0;
  ASSERT_TRUE(getJointLimits(joint("revolute_soft"), l));
  EXPECT_TRUE(l.has_position_limits);
  EXPECT_EQ(-1.5, l.min_position);
  EXPECT_EQ(2.5, l.max_position);
  EXPECT_FALSE(l.angle_wraparound);
  EXPECT_TRUE(l.has_velocity_limits);
  EXPECT_EQ(3.0, l.max_velocity);
  EXPECT_TRUE(l.has_effort_limits);
  EXPECT_EQ(40.0, l.max_effort);
  EXPECT_FALSE(l.has_acceleration_limits);
  EXPECT_FALSE(l.has_jerk_limits);
}

TEST_F(JointLimitsUrdfTest, ContinuousJointWrapsAround)
{
  JointLimits l;
  ASSERT_TRUE(getJointLimits(joint("continuous"), l));
  EXPECT_FALSE(l.has_position_limits);
  EXPECT_TRUE(l.angle_wraparound);
  EXPECT_EQ(8.0, l.max_velocity);
  EXPECT_EQ(2.0, l.max_effort);
}

TEST_F(JointLimitsUrdfTest, PrismaticJoint)
{
  JointLimits l;
  ASSERT_TRUE(getJointLimits(joint("prismatic"), l));
  EXPECT_TRUE(l.has_position_limits);
  EXPECT_EQ(0.0, l.min_position);
  EXPECT_EQ(0.3, l.max_position);
  EXPECT_EQ(0.1, l.max_velocity);
  EXPECT_EQ(100.0, l.max_effort);
}

TEST_F(JointLimitsUrdfTest, NoLimitElementOrNullJointGivesFalse)
{
  JointLimits l;
  l.max_velocity = 42.0;
  EXPECT_FALSE(getJointLimits(joint("continuous_no_limit"), l));
  EXPECT_FALSE(getJointLimits(joint("fixed"), l));
  EXPECT_FALSE(getJointLimits(urdf::JointConstSharedPtr(), l));
  EXPECT_EQ(42.0, l.max_velocity);
  EXPECT_FALSE(l.has_velocity_limits);
}

TEST_F(JointLimitsUrdfTest, SoftLimitsFromSafetyController)
{
  SoftJointLimits s;
  ASSERT_TRUE(getSoftJointLimits(joint("revolute_soft"), s));
  EXPECT_EQ(-1.0, s.min_position);
  EXPECT_EQ(2.0, s.max_position);
  EXPECT_EQ(10.0, s.k_position);
  EXPECT_EQ(0.5, s.k_velocity);

  SoftJointLimits none;
  none.k_position = 3.0;
  EXPECT_FALSE(getSoftJointLimits(joint("continuous"), none));
  EXPECT_FALSE(getSoftJointLimits(urdf::JointConstSharedPtr(), none));
  EXPECT_EQ(3.0, none.k_position);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
