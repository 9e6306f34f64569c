// The diploma's high-level node (figures 2.23-2.24): Diffbot<4> with a ControllerManager in the
// root namespace, a fixed 10 ms period on its own clock (published on /clock), loop
// `robot.read(); cm.update(internal_time, dt); robot.write();` paced by the wall clock.
// Lines the scan does not show (robot.init, the /clock publisher, the AsyncSpinner, the time
// variables) are filled in from the template the diploma names [45]; see README.md.
#include <chrono>
#include <thread>

#include <controller_manager/controller_manager.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include <space_scanner_hw/diffbot.h>

int main(int argc, char **argv)
{
  ros::init(argc, argv, "diffbot");

  ros::NodeHandle nh;

  // This should be set in launch files as well
  nh.setParam("/use_sim_time", true);

  Diffbot<4> robot;
  robot.init(nh);
  ROS_WARN_STREAM("period: " << robot.getPeriod().toSec());

  controller_manager::ControllerManager cm(&robot, nh);

  ros::Publisher clock_publisher = nh.advertise<rosgraph_msgs::Clock>("/clock", 1);

  ros::AsyncSpinner spinner(1);
  spinner.start();

  std::chrono::system_clock::time_point begin = std::chrono::system_clock::now();
  std::chrono::system_clock::time_point end = std::chrono::system_clock::now();

  ros::Time internal_time(0);
  const ros::Duration dt = robot.getPeriod();
  double elapsed_secs = 0;

  while (ros::ok())
  {
    begin = std::chrono::system_clock::now();

    robot.read();

    cm.update(internal_time, dt);

    robot.write();

    end = std::chrono::system_clock::now();

    elapsed_secs = std::chrono::duration_cast<std::chrono::duration<double>>((end - begin)).count();

    if (dt.toSec() - elapsed_secs < 0.0)
    {
      ROS_WARN_STREAM_THROTTLE(0.1, "Control cycle is taking to much time, elapsed: " << elapsed_secs);
    }
    else
    {
      ROS_DEBUG_STREAM_THROTTLE(1.0, "Control cycle is, elapsed: " << elapsed_secs);
      std::this_thread::sleep_for(std::chrono::duration<double>(dt.toSec() - elapsed_secs));
    }

    rosgraph_msgs::Clock clock;
    clock.clock = ros::Time(internal_time);
    clock_publisher.publish(clock);

    internal_time += dt;
  }
  spinner.stop();

  return 0;
}
