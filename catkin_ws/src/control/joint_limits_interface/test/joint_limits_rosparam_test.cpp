// Loading JointLimits / SoftJointLimits from the parameter server (run by test/joint_limits_rosparam.test,
// which loads test/joint_limits_rosparam.yaml).
#include <string>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <joint_limits_interface/joint_limits_rosparam.h>

using namespace joint_limits_interface;

namespace
{
/// Same values as the URDF would give, to check what the parameters overwrite.
JointLimits urdfLike()
{
  JointLimits l;
  l.has_position_limits = true;
  l.min_position = -9.0;
  l.max_position = 9.0;
  l.has_velocity_limits = true;
  l.max_velocity = 9.0;
  l.has_effort_limits = true;
  l.max_effort = 9.0;
  return l;
}
}  // namespace

TEST(JointLimitsRosparamTest, AllLimitsGiven)
{
  ros::NodeHandle nh;
  JointLimits l;
  ASSERT_TRUE(getJointLimits("full_joint", nh, l));
  EXPECT_TRUE(l.has_position_limits);
  EXPECT_EQ(-1.0, l.min_position);
  EXPECT_EQ(1.0, l.max_position);
  EXPECT_TRUE(l.has_velocity_limits);
  EXPECT_EQ(2.0, l.max_velocity);
  EXPECT_TRUE(l.has_acceleration_limits);
  EXPECT_EQ(5.0, l.max_acceleration);
  EXPECT_TRUE(l.has_jerk_limits);
  EXPECT_EQ(100.0, l.max_jerk);
  EXPECT_TRUE(l.has_effort_limits);
  EXPECT_EQ(20.0, l.max_effort);  // given as an integer in the YAML
  EXPECT_FALSE(l.angle_wraparound);
}

TEST(JointLimitsRosparamTest, DiffbotWheelStyle)
{
  // as the diploma's diffbot_limits.yaml: no position limits, wraparound, velocity + acceleration only
  ros::NodeHandle nh;
  JointLimits l = urdfLike();
  ASSERT_TRUE(getJointLimits("left_wheel_joint", nh, l));
  EXPECT_FALSE(l.has_position_limits);
  EXPECT_TRUE(l.angle_wraparound);
  EXPECT_TRUE(l.has_velocity_limits);
  EXPECT_EQ(10.0, l.max_velocity);
  EXPECT_TRUE(l.has_acceleration_limits);
  EXPECT_EQ(4.5, l.max_acceleration);
  EXPECT_FALSE(l.has_jerk_limits);
  EXPECT_FALSE(l.has_effort_limits);
}

TEST(JointLimitsRosparamTest, PartialSpecificationKeepsOtherValues)
{
  ros::NodeHandle nh;
  JointLimits l = urdfLike();
  ASSERT_TRUE(getJointLimits("partial_joint", nh, l));
  // only has_velocity_limits/max_velocity given: the rest keeps the URDF values
  EXPECT_EQ(0.5, l.max_velocity);
  EXPECT_TRUE(l.has_position_limits);
  EXPECT_EQ(-9.0, l.min_position);
  EXPECT_EQ(9.0, l.max_effort);
  // has_position_limits true without min/max, has_effort_limits true without max: unchanged
  JointLimits m = urdfLike();
  ASSERT_TRUE(getJointLimits("incomplete_joint", nh, m));
  EXPECT_TRUE(m.has_position_limits);
  EXPECT_EQ(9.0, m.max_position);
  EXPECT_TRUE(m.has_effort_limits);
  EXPECT_EQ(9.0, m.max_effort);
}

TEST(JointLimitsRosparamTest, MissingJointGivesFalse)
{
  ros::NodeHandle nh;
  JointLimits l = urdfLike();
  EXPECT_FALSE(getJointLimits("no_such_joint", nh, l));
  EXPECT_EQ(9.0, l.max_velocity);
  SoftJointLimits s;
  EXPECT_FALSE(getSoftJointLimits("no_such_joint", nh, s));
}

TEST(JointLimitsRosparamTest, NamespaceOfTheNodeHandle)
{
  ros::NodeHandle robot_nh("my_robot");
  JointLimits l;
  ASSERT_TRUE(getJointLimits("arm_joint", robot_nh, l));
  EXPECT_EQ(0.25, l.max_velocity);
  ros::NodeHandle root_nh;
  EXPECT_FALSE(getJointLimits("arm_joint", root_nh, l));
}

TEST(JointLimitsRosparamTest, SoftLimits)
{
  ros::NodeHandle nh;
  SoftJointLimits s;
  ASSERT_TRUE(getSoftJointLimits("full_joint", nh, s));
  EXPECT_EQ(-0.8, s.min_position);
  EXPECT_EQ(0.8, s.max_position);
  EXPECT_EQ(10.0, s.k_position);
  EXPECT_EQ(0.2, s.k_velocity);

  SoftJointLimits unchanged;
  unchanged.k_position = 3.0;
  EXPECT_FALSE(getSoftJointLimits("left_wheel_joint", nh, unchanged));  // has_soft_limits: false
  EXPECT_FALSE(getSoftJointLimits("incomplete_joint", nh, unchanged));  // k_velocity missing
  EXPECT_FALSE(getSoftJointLimits("partial_joint", nh, unchanged));     // no has_soft_limits
  EXPECT_EQ(3.0, unchanged.k_position);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "joint_limits_rosparam_test");
  return RUN_ALL_TESTS();
}
