// Test fixture: runs DummyRobotHW + ControllerManager on its own simulated clock.
//
// Publishes /clock (set use_sim_time for the other nodes), steps a fixed period of ~period
// [s, default 0.01] per cycle, pacing itself to ~real_time_factor (default 1; 0 = as fast as
// possible). With ~publish_clock false (a second robot in one test) it only keeps its own time. The loop `read();
// cm.update(); write();` runs in its own thread; callbacks are served by an AsyncSpinner. Publishes ~commands
// (std_msgs/Float64MultiArray: the command of every joint, in ~joints order) and ~positions after every cycle.
#include <atomic>
#include <thread>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Float64MultiArray.h>

#include <controller_manager/controller_manager.h>
#include <controller_manager_tests/dummy_robot_hw.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "dummy_robot_hw");
  ros::NodeHandle nh, pnh("~");

  std::vector<std::string> joints{ "joint1", "joint2", "joint3" };
  pnh.getParam("joints", joints);
  double period_s = pnh.param("period", 0.01);
  double real_time_factor = pnh.param("real_time_factor", 1.0);
  const bool publish_clock = pnh.param("publish_clock", true);
  if (period_s <= 0.0)
  {
    ROS_ERROR("dummy_robot_hw: ~period must be > 0 (got %f); using 0.01", period_s);
    period_s = 0.01;
  }

  controller_manager_tests::DummyRobotHW robot(joints);
  controller_manager::ControllerManager cm(&robot, nh);

  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  ros::Publisher cmd_pub = pnh.advertise<std_msgs::Float64MultiArray>("commands", 10);
  ros::Publisher pos_pub = pnh.advertise<std_msgs::Float64MultiArray>("positions", 10);

  ros::AsyncSpinner spinner(2);
  spinner.start();

  std::atomic<bool> running{ true };
  std::thread loop(
      [&]()
      {
        ros::Time t(1.0);  // start at 1 s: time 0 means "no clock yet" to ROS clients
        const ros::Duration period(period_s);
        const double wall_step = real_time_factor > 0.0 ? period_s / real_time_factor : 0.0;
        while (running && ros::ok())
        {
          rosgraph_msgs::Clock clock;
          clock.clock = t;
          if (publish_clock)
            clock_pub.publish(clock);

          robot.read(t, period);
          cm.update(t, period);
          robot.write(t, period);

          std_msgs::Float64MultiArray cmds, positions;
          for (size_t i = 0; i < joints.size(); ++i)
          {
            cmds.data.push_back(robot.command(i));
            positions.data.push_back(robot.position(i));
          }
          cmd_pub.publish(cmds);
          pos_pub.publish(positions);

          t += period;
          if (wall_step > 0.0)
            ros::WallDuration(wall_step).sleep();
        }
      });

  ros::waitForShutdown();
  running = false;
  loop.join();
  return 0;
}
