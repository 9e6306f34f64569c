// rostest node: Pid::init reads its parameters as control_toolbox does, refuses a missing p,
// serves the gains with dynamic_reconfigure and publishes PidState when asked to.
#include <gtest/gtest.h>

#include <atomic>

#include <control_msgs/PidState.h>
#include <control_toolbox/pid.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

using control_toolbox::Pid;

TEST(PidParams, ReadsGainsAndClamps)
{
  Pid pid;
  ASSERT_TRUE(pid.init(ros::NodeHandle("/full_pid")));
  const Pid::Gains g = pid.getGains();
  EXPECT_EQ(100.0, g.p_gain_);
  EXPECT_EQ(0.01, g.i_gain_);
  EXPECT_EQ(10.0, g.d_gain_);
  EXPECT_EQ(2.0, g.i_max_);   // from i_clamp
  EXPECT_EQ(-0.5, g.i_min_);  // i_clamp_min overrides, sign forced to <= 0
  EXPECT_TRUE(g.antiwindup_);
}

TEST(PidParams, DefaultsWithOnlyP)
{
  Pid pid;
  ASSERT_TRUE(pid.initParam("/p_only"));
  const Pid::Gains g = pid.getGains();
  EXPECT_EQ(5.0, g.p_gain_);
  EXPECT_EQ(0.0, g.i_gain_);
  EXPECT_EQ(0.0, g.d_gain_);
  EXPECT_EQ(0.0, g.i_max_);
  EXPECT_EQ(0.0, g.i_min_);
  EXPECT_FALSE(g.antiwindup_);
}

TEST(PidParams, MissingPFails)
{
  Pid pid;
  EXPECT_FALSE(pid.init(ros::NodeHandle("/no_p")));
  EXPECT_FALSE(pid.init(ros::NodeHandle("/no_p"), true));
}

TEST(PidParams, DynamicReconfigureSetsGains)
{
  Pid pid;
  ros::NodeHandle nh("/reconf_pid");
  ASSERT_TRUE(pid.init(nh));
  ASSERT_TRUE(ros::service::waitForService("/reconf_pid/set_parameters", ros::Duration(60.0)))
      << "no dynamic_reconfigure service in the pid namespace";
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::DoubleParameter p;
  p.name = "p";
  p.value = 7.0;
  srv.request.config.doubles.push_back(p);
  dynamic_reconfigure::DoubleParameter d;
  d.name = "d";
  d.value = 0.25;
  srv.request.config.doubles.push_back(d);
  ASSERT_TRUE(ros::service::call("/reconf_pid/set_parameters", srv));
  EXPECT_EQ(7.0, pid.getGains().p_gain_);
  EXPECT_EQ(0.25, pid.getGains().d_gain_);
  EXPECT_EQ(1.0, pid.getGains().i_gain_);  // untouched
  // the server shows the pid's values on the parameter server
  double p_param = 0.0;
  ASSERT_TRUE(nh.getParam("p", p_param));
  EXPECT_EQ(7.0, p_param);
  // and setGains from code shows up in the server's parameters
  pid.setGains(3.0, 1.0, 0.0, 1.0, -1.0);
  ASSERT_TRUE(nh.getParam("p", p_param));
  EXPECT_EQ(3.0, p_param);
}

TEST(PidParams, PublishesStateWhenAsked)
{
  Pid pid;
  ros::NodeHandle nh("/state_pid");
  ASSERT_TRUE(pid.init(nh));
  std::atomic<int> count(0);
  std::atomic<double> last_output(0.0);
  ros::Subscriber sub = nh.subscribe<control_msgs::PidState>("state", 10,
                                                             [&](const control_msgs::PidState::ConstPtr& msg)
                                                             {
                                                               last_output = msg->output;
                                                               ++count;
                                                             });
  for (int i = 0; i < 6000 && sub.getNumPublishers() == 0; ++i)
    ros::WallDuration(0.01).sleep();
  ASSERT_EQ(1u, sub.getNumPublishers()) << "nobody publishes /state_pid/state";
  for (int i = 0; i < 6000 && count == 0; ++i)
  {
    pid.computeCommand(0.5, ros::Duration(0.01));
    ros::WallDuration(0.01).sleep();
  }
  ASSERT_GT(count, 0) << "no PidState received";
  EXPECT_DOUBLE_EQ(2.0 * 0.5, last_output);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "pid_params_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
