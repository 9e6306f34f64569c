// RobotHW defaults and checkForConflict.
#include <gtest/gtest.h>

#include <hardware_interface/robot_hw.h>

using namespace hardware_interface;

static ControllerInfo info(const std::string& name, const std::string& iface, const std::set<std::string>& res)
{
  ControllerInfo c;
  c.name = name;
  c.type = "test/Type";
  c.claimed_resources.emplace_back(iface, res);
  return c;
}

TEST(RobotHWTest, NoConflictOnDisjointResources)
{
  RobotHW hw;
  std::list<ControllerInfo> l{ info("a", "hardware_interface::EffortJointInterface", { "j1" }),
                               info("b", "hardware_interface::EffortJointInterface", { "j2" }),
                               info("c", "hardware_interface::JointStateInterface", {}) };
  EXPECT_FALSE(hw.checkForConflict(l));
}

TEST(RobotHWTest, ConflictOnSharedResource)
{
  RobotHW hw;
  std::list<ControllerInfo> l{ info("a", "hardware_interface::EffortJointInterface", { "j1", "j2" }),
                               info("b", "hardware_interface::VelocityJointInterface", { "j2" }) };
  EXPECT_TRUE(hw.checkForConflict(l));
}

TEST(RobotHWTest, Defaults)
{
  RobotHW hw;
  ros::NodeHandle* no_nh = nullptr;
  (void)no_nh;
  std::list<ControllerInfo> empty;
  EXPECT_TRUE(hw.prepareSwitch(empty, empty));
  hw.doSwitch(empty, empty);
  EXPECT_EQ(RobotHW::SwitchState::DONE, hw.switchResult());
  hw.read(ros::Time(1.0), ros::Duration(0.01));
  hw.write(ros::Time(1.0), ros::Duration(0.01));
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
