// InterfaceManager: registration by type, replacement, sub-managers, combination, names/resources.
#include <gtest/gtest.h>

#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/robot_hw.h>

using namespace hardware_interface;

struct NotAResourceManager : public HardwareInterface
{
  int value = 0;
};

class InterfaceManagerTest : public ::testing::Test
{
protected:
  double pos[2] = { 1.0, 2.0 }, vel[2] = { 0, 0 }, eff[2] = { 0, 0 }, cmd[2] = { 0, 0 };
  JointStateHandle hs1{ "j1", &pos[0], &vel[0], &eff[0] };
  JointStateHandle hs2{ "j2", &pos[1], &vel[1], &eff[1] };
};

TEST_F(InterfaceManagerTest, RegisterAndGet)
{
  InterfaceManager im;
  JointStateInterface jsi;
  jsi.registerHandle(hs1);
  EXPECT_EQ(nullptr, im.get<JointStateInterface>());
  im.registerInterface(&jsi);
  EXPECT_EQ(&jsi, im.get<JointStateInterface>());
  EXPECT_EQ(nullptr, im.get<EffortJointInterface>());
  std::vector<std::string> names = im.getNames();
  ASSERT_EQ(1u, names.size());
  EXPECT_EQ("hardware_interface::JointStateInterface", names[0]);
  EXPECT_EQ(std::vector<std::string>{ "j1" }, im.getInterfaceResources("hardware_interface::JointStateInterface"));
  EXPECT_TRUE(im.getInterfaceResources("hardware_interface::EffortJointInterface").empty());
}

TEST_F(InterfaceManagerTest, ReplaceSameType)
{
  InterfaceManager im;
  JointStateInterface a, b;
  im.registerInterface(&a);
  im.registerInterface(&b);  // warns "Replacing previously registered interface"
  EXPECT_EQ(&b, im.get<JointStateInterface>());
  EXPECT_EQ(1u, im.getNames().size());
}

TEST_F(InterfaceManagerTest, DistinctCommandTypes)
{
  InterfaceManager im;
  EffortJointInterface effort;
  VelocityJointInterface velocity;
  im.registerInterface(&effort);
  im.registerInterface(&velocity);
  EXPECT_EQ(&effort, im.get<EffortJointInterface>());
  EXPECT_EQ(&velocity, im.get<VelocityJointInterface>());
  EXPECT_EQ(nullptr, im.get<PositionJointInterface>());
}

TEST_F(InterfaceManagerTest, SubManagersAreCombined)
{
  RobotHW part1, part2, combined;
  JointStateInterface jsi1, jsi2;
  EffortJointInterface eji1;
  jsi1.registerHandle(hs1);
  jsi2.registerHandle(hs2);
  eji1.registerHandle(JointHandle(hs1, &cmd[0]));
  part1.registerInterface(&jsi1);
  part1.registerInterface(&eji1);
  part2.registerInterface(&jsi2);
  combined.registerInterfaceManager(&part1);
  combined.registerInterfaceManager(&part2);

  // only one effort interface: returned as is
  EXPECT_EQ(&eji1, combined.get<EffortJointInterface>());
  // two state interfaces: a new combined one with both joints, cached
  JointStateInterface* js = combined.get<JointStateInterface>();
  ASSERT_NE(nullptr, js);
  EXPECT_NE(&jsi1, js);
  EXPECT_EQ((std::vector<std::string>{ "j1", "j2" }), js->getNames());
  EXPECT_DOUBLE_EQ(2.0, js->getHandle("j2").getPosition());
  EXPECT_EQ(js, combined.get<JointStateInterface>());
  EXPECT_EQ(3u, combined.getNames().size());
  EXPECT_EQ((std::vector<std::string>{ "j1", "j2" }),
            combined.getInterfaceResources("hardware_interface::JointStateInterface"));
}

TEST_F(InterfaceManagerTest, NonResourceManagersAreNotCombined)
{
  InterfaceManager a, b, top;
  NotAResourceManager x, y;
  a.registerInterface(&x);
  b.registerInterface(&y);
  top.registerInterfaceManager(&a);
  EXPECT_EQ(&x, top.get<NotAResourceManager>());
  top.registerInterfaceManager(&b);
  EXPECT_EQ(nullptr, top.get<NotAResourceManager>());  // logs an error
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
