// ResourceManager / HardwareResourceManager: registration, replacement, lookup errors, claims.
#include <gtest/gtest.h>

#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>

using namespace hardware_interface;

class ResourceManagerTest : public ::testing::Test
{
protected:
  double pos1 = 1.0, vel1 = 2.0, eff1 = 3.0, cmd1 = 0.0;
  double pos2 = 4.0, vel2 = 5.0, eff2 = 6.0, cmd2 = 0.0;
  JointStateHandle hs1{ "j1", &pos1, &vel1, &eff1 };
  JointStateHandle hs2{ "j2", &pos2, &vel2, &eff2 };
};

TEST_F(ResourceManagerTest, RegisterAndGetSortedNames)
{
  ResourceManager<JointStateHandle> rm;
  rm.registerHandle(hs2);
  rm.registerHandle(hs1);
  std::vector<std::string> names = rm.getNames();
  ASSERT_EQ(2u, names.size());
  EXPECT_EQ("j1", names[0]);
  EXPECT_EQ("j2", names[1]);
  EXPECT_DOUBLE_EQ(4.0, rm.getHandle("j2").getPosition());
}

TEST_F(ResourceManagerTest, ReplaceKeepsOneHandle)
{
  ResourceManager<JointStateHandle> rm;
  rm.registerHandle(hs1);
  JointStateHandle other("j1", &pos2, &vel2, &eff2);
  rm.registerHandle(other);  // warns "Replacing previously registered handle"
  ASSERT_EQ(1u, rm.getNames().size());
  EXPECT_DOUBLE_EQ(4.0, rm.getHandle("j1").getPosition());
}

TEST_F(ResourceManagerTest, MissingHandleThrowsLogicError)
{
  ResourceManager<JointStateHandle> rm;
  rm.registerHandle(hs1);
  try
  {
    rm.getHandle("nope");
    FAIL() << "getHandle of a missing name must throw";
  }
  catch (const std::logic_error& e)
  {
    EXPECT_EQ(
        "Could not find resource 'nope' in "
        "'hardware_interface::ResourceManager<hardware_interface::JointStateHandle>'.",
        std::string(e.what()));
  }
}

TEST_F(ResourceManagerTest, HardwareResourceManagerWrapsException)
{
  JointStateInterface iface;
  iface.registerHandle(hs1);
  try
  {
    iface.getHandle("nope");
    FAIL() << "getHandle of a missing name must throw";
  }
  catch (const HardwareInterfaceException& e)
  {
    EXPECT_NE(std::string::npos, std::string(e.what()).find("Could not find resource 'nope' in '"));
  }
}

TEST_F(ResourceManagerTest, StateInterfaceDoesNotClaim)
{
  JointStateInterface iface;
  iface.registerHandle(hs1);
  iface.getHandle("j1");
  EXPECT_TRUE(iface.getClaims().empty());
}

TEST_F(ResourceManagerTest, CommandInterfaceClaims)
{
  EffortJointInterface iface;
  iface.registerHandle(JointHandle(hs1, &cmd1));
  iface.registerHandle(JointHandle(hs2, &cmd2));
  JointHandle h = iface.getHandle("j2");
  h.setCommand(7.0);
  EXPECT_DOUBLE_EQ(7.0, cmd2);
  std::set<std::string> claims = iface.getClaims();
  ASSERT_EQ(1u, claims.size());
  EXPECT_EQ("j2", *claims.begin());
  iface.clearClaims();
  EXPECT_TRUE(iface.getClaims().empty());
  EXPECT_THROW(iface.getHandle("nope"), HardwareInterfaceException);
  EXPECT_TRUE(iface.getClaims().empty());  // a failed lookup claims nothing
}

TEST_F(ResourceManagerTest, ConcatManagers)
{
  JointStateInterface a, b, combined;
  a.registerHandle(hs1);
  b.registerHandle(hs2);
  std::vector<JointStateInterface*> managers{ &a, &b };
  ResourceManager<JointStateHandle>::concatManagers(managers, &combined);
  EXPECT_EQ((std::vector<std::string>{ "j1", "j2" }), combined.getNames());
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
