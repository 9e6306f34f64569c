// `rosrun diff_drive_controller diffbot`: the diffbot RobotHW with a ControllerManager in the
// node's namespace, stepping a fixed 10 ms on its own clock (published on /clock, and
// /use_sim_time set) in a loop thread `read(); cm.update(); write();`, at most as fast as
// the wall clock; callbacks on an AsyncSpinner. ~num_joints (2): wheel_0_joint ... wheel_<n-1>_joint.
#include <chrono>
#include <thread>

#include <controller_manager/controller_manager.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include "diffbot.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "diffbot");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  nh.setParam("/use_sim_time", true);  // should be set in the launch file as well

  int num_joints = 2;
  pnh.param("num_joints", num_joints, 2);
  if (num_joints < 2)
  {
    ROS_ERROR("diffbot: ~num_joints must be at least 2 (got %d)", num_joints);
    return 1;
  }
  Diffbot robot(static_cast<unsigned int>(num_joints));
  ROS_INFO_STREAM("diffbot: " << num_joints << " wheel joints, period " << robot.getPeriod().toSec() << " s");
  controller_manager::ControllerManager cm(&robot, nh);
  ros::Publisher clock_publisher = nh.advertise<rosgraph_msgs::Clock>("/clock", 1);

  ros::AsyncSpinner spinner(1);
  spinner.start();

  ros::Time internal_time(0);
  const ros::Duration dt = robot.getPeriod();
  while (ros::ok())
  {
    const auto begin = std::chrono::steady_clock::now();
    robot.read(internal_time, dt);
    cm.update(internal_time, dt);
    robot.write(internal_time, dt);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    if (dt.toSec() - elapsed < 0.0)
      ROS_WARN_STREAM_THROTTLE(1.0, "Control cycle is taking to much time, elapsed: " << elapsed);
    else
      std::this_thread::sleep_for(std::chrono::duration<double>(dt.toSec() - elapsed));

    rosgraph_msgs::Clock clock;
    clock.clock = internal_time;
    clock_publisher.publish(clock);
    internal_time += dt;
  }
  spinner.stop();
  return 0;
}
