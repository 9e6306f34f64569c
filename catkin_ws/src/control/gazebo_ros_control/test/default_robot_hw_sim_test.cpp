// DefaultRobotHWSim on a BridgeModel: interfaces per joint, state copy, limits, e-stop.
// Needs no ROS master.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <gazebo_ros_control/default_robot_hw_sim.h>

using namespace gazebo_ros_control;

namespace
{
BridgeJoint joint(const std::string& name, JointInterface iface)
{
  BridgeJoint j;
  j.name = name;
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

class HwSim : public ::testing::Test
{
protected:
  HwSim()
    : model_({ joint("eff", JointInterface::EFFORT), joint("vel", JointInterface::VELOCITY),
               joint("pos", JointInterface::POSITION), joint("state", JointInterface::STATE) })
  {
    ros::NodeHandle nh;
    EXPECT_TRUE(hw_.initSim("/robot", nh, &model_));
    std::string error;
    EXPECT_TRUE(model_.setState({ "eff", "vel", "pos", "state" }, { 0.1, 0.2, 0.3, 0.4 }, { 1, 2, 0, 4 },
                                { 5, 6, 7, 8 }, &error));
    hw_.readSim(ros::Time(1.0), ros::Duration(0.01));
  }
  BridgeModel model_;
  DefaultRobotHWSim hw_;
};
}  // namespace

TEST_F(HwSim, RegistersInterfaces)
{
  auto* js = hw_.get<hardware_interface::JointStateInterface>();
  ASSERT_NE(nullptr, js);
  EXPECT_EQ(4u, js->getNames().size());
  EXPECT_DOUBLE_EQ(0.4, js->getHandle("state").getPosition());
  EXPECT_DOUBLE_EQ(2.0, js->getHandle("vel").getVelocity());
  EXPECT_DOUBLE_EQ(7.0, js->getHandle("pos").getEffort());
  ASSERT_NE(nullptr, hw_.get<hardware_interface::EffortJointInterface>());
  EXPECT_EQ(std::vector<std::string>{ "eff" }, hw_.get<hardware_interface::EffortJointInterface>()->getNames());
  EXPECT_EQ(std::vector<std::string>{ "vel" }, hw_.get<hardware_interface::VelocityJointInterface>()->getNames());
  EXPECT_EQ(std::vector<std::string>{ "pos" }, hw_.get<hardware_interface::PositionJointInterface>()->getNames());
}

TEST_F(HwSim, NoCommandStaysNaN)
{
  hw_.writeSim(ros::Time(1.0), ros::Duration(0.01));
  EXPECT_TRUE(std::isnan(model_.command(0)));
  EXPECT_TRUE(std::isnan(model_.command(1)));
  EXPECT_TRUE(std::isnan(model_.command(2)));
}

TEST_F(HwSim, CommandsLimited)
{
  hw_.get<hardware_interface::EffortJointInterface>()->getHandle("eff").setCommand(50.0);
  hw_.get<hardware_interface::VelocityJointInterface>()->getHandle("vel").setCommand(-9.0);
  auto pos = hw_.get<hardware_interface::PositionJointInterface>()->getHandle("pos");
  pos.setCommand(1.0);
  hw_.writeSim(ros::Time(1.0), ros::Duration(0.1));
  EXPECT_DOUBLE_EQ(10.0, model_.command(0));
  EXPECT_DOUBLE_EQ(-3.0, model_.command(1));
  EXPECT_NEAR(0.6, model_.command(2), 1e-12);  // 0.3 + 3 rad/s * 0.1 s
  EXPECT_NEAR(0.6, pos.getCommand(), 1e-12);   // the limited value replaces the command
}

TEST_F(HwSim, EStopZeroesAndHolds)
{
  hw_.get<hardware_interface::EffortJointInterface>()->getHandle("eff").setCommand(5.0);
  hw_.get<hardware_interface::VelocityJointInterface>()->getHandle("vel").setCommand(1.0);
  hw_.get<hardware_interface::PositionJointInterface>()->getHandle("pos").setCommand(1.0);
  hw_.eStopActive(true);
  hw_.writeSim(ros::Time(1.0), ros::Duration(0.01));
  EXPECT_DOUBLE_EQ(0.0, model_.command(0));
  EXPECT_DOUBLE_EQ(0.0, model_.command(1));
  EXPECT_DOUBLE_EQ(0.3, model_.command(2));
  std::string error;
  ASSERT_TRUE(model_.setState({ "eff", "vel", "pos", "state" }, { 0, 0, 0.9, 0 }, {}, {}, &error));
  hw_.readSim(ros::Time(1.01), ros::Duration(0.01));
  hw_.writeSim(ros::Time(1.01), ros::Duration(0.01));
  EXPECT_DOUBLE_EQ(0.3, model_.command(2));  // held where the stop began
  hw_.eStopActive(false);
  hw_.writeSim(ros::Time(1.02), ros::Duration(0.01));
  EXPECT_DOUBLE_EQ(5.0, model_.command(0));
  EXPECT_DOUBLE_EQ(1.0, model_.command(1));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "gtest_gazebo_ros_control_hw_sim",
            ros::init_options::AnonymousName | ros::init_options::NoRosout);
  // no ROS master in unit tests: the NodeHandle is only passed through, do not wait for one
  ros::master::setRetryTimeout(ros::WallDuration(0.2));
  return RUN_ALL_TESTS();
}
