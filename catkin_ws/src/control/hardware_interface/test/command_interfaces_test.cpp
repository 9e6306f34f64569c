// PosVel / PosVelAcc joint interfaces and the actuator interfaces: handles by name, the data they
// point to, claims, and HardwareInterfaceException naming the interface on unknown names.
#include <string>
#include <functional>

#include <gtest/gtest.h>

#include <hardware_interface/actuator_command_interface.h>
#include <hardware_interface/actuator_state_interface.h>
#include <hardware_interface/posvel_command_interface.h>
#include <hardware_interface/posvelacc_command_interface.h>

using namespace hardware_interface;

static std::string errorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const HardwareInterfaceException& e)
  {
    return e.what();
  }
  return "";
}

TEST(PosVelAccJointHandleTest, NullPointers)
{
  double pos = 0, vel = 0, eff = 0, cp = 0, cv = 0, ca = 0;
  JointStateHandle js("j", &pos, &vel, &eff);
  EXPECT_NO_THROW(PosVelAccJointHandle(js, &cp, &cv, &ca));
  EXPECT_EQ("Cannot create handle 'j'. Command position pointer is null.",
            errorOf([&] { PosVelAccJointHandle(js, nullptr, &cv, &ca); }));
  EXPECT_EQ("Cannot create handle 'j'. Command velocity  pointer is null.",
            errorOf([&] { PosVelAccJointHandle(js, &cp, nullptr, &ca); }));
  EXPECT_EQ("Cannot create handle 'j'. Command acceleration data pointer is null.",
            errorOf([&] { PosVelAccJointHandle(js, &cp, &cv, nullptr); }));
}

TEST(PosVelAccJointInterfaceTest, HandlesByNameAndClaims)
{
  double pos1 = 1, vel1 = 2, eff1 = 3, cp1 = 0, cv1 = 0, ca1 = 0;
  double pos2 = 4, vel2 = 5, eff2 = 6, cp2 = 0, cv2 = 0, ca2 = 0;
  PosVelAccJointInterface iface;
  iface.registerHandle(PosVelAccJointHandle(JointStateHandle("a", &pos1, &vel1, &eff1), &cp1, &cv1, &ca1));
  iface.registerHandle(PosVelAccJointHandle(JointStateHandle("b", &pos2, &vel2, &eff2), &cp2, &cv2, &ca2));
  EXPECT_TRUE(iface.getClaims().empty());

  PosVelAccJointHandle b = iface.getHandle("b");
  EXPECT_EQ("b", b.getName());
  EXPECT_DOUBLE_EQ(4.0, b.getPosition());
  EXPECT_DOUBLE_EQ(5.0, b.getVelocity());
  EXPECT_DOUBLE_EQ(6.0, b.getEffort());
  b.setCommand(-1.0, -2.0, -3.0);
  EXPECT_DOUBLE_EQ(-1.0, cp2);
  EXPECT_DOUBLE_EQ(-2.0, cv2);
  EXPECT_DOUBLE_EQ(-3.0, ca2);
  EXPECT_DOUBLE_EQ(-3.0, b.getCommandAcceleration());
  b.setCommand(7.0, 8.0);  // the PosVel part alone leaves the acceleration
  EXPECT_DOUBLE_EQ(7.0, b.getCommandPosition());
  EXPECT_DOUBLE_EQ(8.0, b.getCommandVelocity());
  EXPECT_DOUBLE_EQ(-3.0, ca2);
  EXPECT_DOUBLE_EQ(0.0, cp1);  // the other joint is untouched

  iface.getHandle("a");
  iface.getHandle("a");
  EXPECT_EQ(2u, iface.getClaims().size());
  EXPECT_EQ("Could not find resource 'c' in 'hardware_interface::PosVelAccJointInterface'.",
            errorOf([&] { iface.getHandle("c"); }));
}

TEST(PosVelJointInterfaceTest, UnknownNameNamesTheInterface)
{
  PosVelJointInterface iface;
  EXPECT_EQ("Could not find resource 'x' in 'hardware_interface::PosVelJointInterface'.",
            errorOf([&] { iface.getHandle("x"); }));
  double pos = 0, vel = 0, eff = 0, cp = 0;
  EXPECT_EQ("Cannot create handle 'j'. Command velocity  pointer is null.",
            errorOf([&] { PosVelJointHandle(JointStateHandle("j", &pos, &vel, &eff), &cp, nullptr); }));
}

TEST(ActuatorStateInterfaceTest, HandlesByName)
{
  double pos1 = 1, vel1 = 2, eff1 = 3, pos2 = 4, vel2 = 5, eff2 = 6;
  ActuatorStateInterface iface;
  iface.registerHandle(ActuatorStateHandle("m1", &pos1, &vel1, &eff1));
  iface.registerHandle(ActuatorStateHandle("m2", &pos2, &vel2, &eff2));
  EXPECT_EQ((std::vector<std::string>{ "m1", "m2" }), iface.getNames());
  ActuatorStateHandle h = iface.getHandle("m2");
  EXPECT_DOUBLE_EQ(4.0, h.getPosition());
  pos2 = 40.0;  // a handle reads through to the data
  EXPECT_DOUBLE_EQ(40.0, h.getPosition());
  EXPECT_DOUBLE_EQ(6.0, h.getEffort());
  EXPECT_TRUE(iface.getClaims().empty());
  EXPECT_EQ("Could not find resource 'm3' in 'hardware_interface::ActuatorStateInterface'.",
            errorOf([&] { iface.getHandle("m3"); }));
  EXPECT_EQ("Cannot create handle 'm'. Velocity data pointer is null.",
            errorOf([&] { ActuatorStateHandle("m", &pos1, nullptr, &eff1); }));
}

TEST(ActuatorCommandInterfaceTest, HandlesByNameNoClaims)
{
  double pos = 1, vel = 2, eff = 3, cmd1 = 0, cmd2 = 0;
  ActuatorStateHandle s1("m1", &pos, &vel, &eff), s2("m2", &pos, &vel, &eff);
  EffortActuatorInterface iface;
  iface.registerHandle(ActuatorHandle(s1, &cmd1));
  iface.registerHandle(ActuatorHandle(s2, &cmd2));
  ActuatorHandle h = iface.getHandle("m1");
  h.setCommand(-1.5);
  EXPECT_DOUBLE_EQ(-1.5, cmd1);
  EXPECT_DOUBLE_EQ(0.0, cmd2);
  EXPECT_EQ(&cmd1, h.getCommandPtr());
  *h.getCommandPtr() = 2.5;
  EXPECT_DOUBLE_EQ(2.5, h.getCommand());
  iface.getHandle("m2");
  EXPECT_TRUE(iface.getClaims().empty());
  EXPECT_EQ("Could not find resource 'x' in 'hardware_interface::EffortActuatorInterface'.",
            errorOf([&] { iface.getHandle("x"); }));
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
