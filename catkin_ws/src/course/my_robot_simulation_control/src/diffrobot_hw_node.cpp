// diffrobot_hw_node (in the robot namespace, e.g. <node ns="/diffrobot" ...>): DiffRobotHW and a
// controller manager, in the classic ros_control loop read(); cm.update(); write(); paced by
// the simulator: one iteration per joint state it publishes, on sim time.
#include <controller_manager/controller_manager.h>
#include <ros/ros.h>

#include <my_robot_simulation_control/diffrobot_hw.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "diffrobot_hw");
  ros::NodeHandle root_nh;  // the robot namespace
  ros::NodeHandle robot_hw_nh("~");
  my_robot_simulation_control::DiffRobotHW robot;
  if (!robot.init(root_nh, robot_hw_nh))
    return 1;
  controller_manager::ControllerManager cm(&robot, root_nh);
  double control_period = 0.001;
  root_nh.param("ode_sim/control_period", control_period, control_period);

  ros::AsyncSpinner spinner(1);  // controller_manager services, command topics
  spinner.start();
  ros::Time last;
  while (ros::ok())
  {
    if (!robot.waitForState(ros::WallDuration(0.5)))
      continue;
    const ros::Time now = robot.stateTime();
    const ros::Duration period = (last.isZero() || now <= last) ? ros::Duration(control_period) : now - last;
    last = now;
    robot.read(now, period);
    cm.update(now, period);
    robot.write(now, period);
  }
  spinner.stop();
  return 0;
}
