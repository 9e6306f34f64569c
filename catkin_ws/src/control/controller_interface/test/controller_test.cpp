// Controller<T> / MultiInterfaceController lifecycle, interface lookup and claimed resources.
#include <gtest/gtest.h>

#include <ros/ros.h>

#include <controller_interface/controller.h>
#include <controller_interface/multi_interface_controller.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>

using namespace hardware_interface;
using controller_interface::ControllerBase;

class TwoJointHW : public RobotHW
{
public:
  TwoJointHW()
  {
    for (int i = 0; i < 2; ++i)
    {
      JointStateHandle js(names[i], &pos[i], &vel[i], &eff[i]);
      jsi.registerHandle(js);
      eji.registerHandle(JointHandle(js, &cmd[i]));
    }
    registerInterface(&jsi);
    registerInterface(&eji);
  }
  std::string names[2] = { "j1", "j2" };
  double pos[2] = { 0, 0 }, vel[2] = { 0, 0 }, eff[2] = { 0, 0 }, cmd[2] = { 0, 0 };
  JointStateInterface jsi;
  EffortJointInterface eji;
};

class EffortCtrl : public controller_interface::Controller<EffortJointInterface>
{
public:
  bool init(EffortJointInterface* hw, ros::NodeHandle& /*nh*/) override
  {
    if (fail)
      return false;
    handle = hw->getHandle("j2");
    return true;
  }
  void starting(const ros::Time&) override { ++starts; }
  void update(const ros::Time&, const ros::Duration&) override { handle.setCommand(handle.getCommand() + 1.0); }
  void stopping(const ros::Time&) override { ++stops; }
  JointHandle handle;
  bool fail = false;
  int starts = 0, stops = 0;
};

class VelocityCtrl : public controller_interface::Controller<VelocityJointInterface>
{
public:
  void update(const ros::Time&, const ros::Duration&) override {}
};

class MultiCtrl : public controller_interface::MultiInterfaceController<JointStateInterface, EffortJointInterface,
                                                                        VelocityJointInterface>
{
public:
  explicit MultiCtrl(bool optional)
    : controller_interface::MultiInterfaceController<JointStateInterface, EffortJointInterface, VelocityJointInterface>(
          optional)
  {
  }
  bool init(RobotHW* hw, ros::NodeHandle&) override
  {
    saw_velocity = hw->get<VelocityJointInterface>() != nullptr;
    hw->get<JointStateInterface>()->getHandle("j1");
    hw->get<EffortJointInterface>()->getHandle("j1");
    return true;
  }
  void update(const ros::Time&, const ros::Duration&) override {}
  bool saw_velocity = true;
};

class ControllerTest : public ::testing::Test
{
protected:
  TwoJointHW hw;
  ros::NodeHandle nh;
  ControllerBase::ClaimedResources claimed;
};

TEST_F(ControllerTest, Lifecycle)
{
  EffortCtrl c;
  ControllerBase& base = c;
  EXPECT_FALSE(base.startRequest(ros::Time(1.0)));  // not initialised
  EXPECT_FALSE(base.stopRequest(ros::Time(1.0)));
  ASSERT_TRUE(base.initRequest(&hw, nh, nh, claimed));
  EXPECT_TRUE(c.isInitialized());
  ASSERT_EQ(1u, claimed.size());
  EXPECT_EQ("hardware_interface::EffortJointInterface", claimed[0].hardware_interface);
  EXPECT_EQ(std::set<std::string>{ "j2" }, claimed[0].resources);
  EXPECT_TRUE(hw.eji.getClaims().empty());

  base.updateRequest(ros::Time(1.0), ros::Duration(0.01));  // not running: no update
  EXPECT_DOUBLE_EQ(0.0, hw.cmd[1]);
  EXPECT_TRUE(base.startRequest(ros::Time(1.0)));
  EXPECT_TRUE(c.isRunning());
  base.updateRequest(ros::Time(1.0), ros::Duration(0.01));
  base.updateRequest(ros::Time(1.0), ros::Duration(0.01));
  EXPECT_DOUBLE_EQ(2.0, hw.cmd[1]);
  EXPECT_TRUE(base.stopRequest(ros::Time(1.0)));
  EXPECT_TRUE(c.isStopped());
  base.updateRequest(ros::Time(1.0), ros::Duration(0.01));
  EXPECT_DOUBLE_EQ(2.0, hw.cmd[1]);
  EXPECT_TRUE(base.waitRequest(ros::Time(1.0)));
  EXPECT_TRUE(c.isWaiting());
  EXPECT_TRUE(base.abortRequest(ros::Time(1.0)));
  EXPECT_TRUE(c.isAborted());
  EXPECT_EQ(1, c.starts);
  EXPECT_EQ(1, c.stops);
  EXPECT_FALSE(base.initRequest(&hw, nh, nh, claimed));  // only once
}

TEST_F(ControllerTest, InitFailure)
{
  EffortCtrl c;
  c.fail = true;
  EXPECT_FALSE(static_cast<ControllerBase&>(c).initRequest(&hw, nh, nh, claimed));
  EXPECT_EQ(ControllerBase::ControllerState::CONSTRUCTED, c.state_);
}

TEST_F(ControllerTest, MissingInterface)
{
  VelocityCtrl c;
  EXPECT_FALSE(static_cast<ControllerBase&>(c).initRequest(&hw, nh, nh, claimed));
}

TEST_F(ControllerTest, MultiInterfaceRequiredMissing)
{
  MultiCtrl c(false);
  EXPECT_FALSE(static_cast<ControllerBase&>(c).initRequest(&hw, nh, nh, claimed));
}

TEST_F(ControllerTest, MultiInterfaceOptional)
{
  MultiCtrl c(true);
  ASSERT_TRUE(static_cast<ControllerBase&>(c).initRequest(&hw, nh, nh, claimed));
  EXPECT_FALSE(c.saw_velocity);
  ASSERT_EQ(2u, claimed.size());
  EXPECT_EQ("hardware_interface::JointStateInterface", claimed[0].hardware_interface);
  EXPECT_TRUE(claimed[0].resources.empty());
  EXPECT_EQ("hardware_interface::EffortJointInterface", claimed[1].hardware_interface);
  EXPECT_EQ(std::set<std::string>{ "j1" }, claimed[1].resources);
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  // No ROS master in unit tests: the NodeHandles are only passed through, so do not wait for one.
  ros::init(argc, argv, "controller_interface_test", ros::init_options::AnonymousName | ros::init_options::NoRosout);
  ros::master::setRetryTimeout(ros::WallDuration(0.2));
  return RUN_ALL_TESTS();
}
