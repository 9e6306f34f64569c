// control_loop_bench [UPDATES]: the cost of ControllerManager::update for a 4-wheel robot with
// joint_state_controller and diff_drive_controller (bench/control_loop starts it on a private
// roscore). Prints the mean, p99 and max wall time of update() and the mean as a fraction of a
// 1 kHz control period (target <= 0.02).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include <controller_manager/controller_manager.h>
#include <geometry_msgs/Twist.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <ros/ros.h>

namespace
{
class FourWheels : public hardware_interface::RobotHW
{
public:
  FourWheels()
  {
    for (int i = 0; i < 4; ++i)
    {
      const std::string name = "wheel_" + std::to_string(i + 1) + "_joint";
      hardware_interface::JointStateHandle sh(name, &pos_[i], &vel_[i], &eff_[i]);
      state_.registerHandle(sh);
      velocity_.registerHandle(hardware_interface::JointHandle(sh, &cmd_[i]));
    }
    registerInterface(&state_);
    registerInterface(&velocity_);
  }
  /// The wheels follow their velocity commands exactly.
  void step(double dt)
  {
    for (int i = 0; i < 4; ++i)
    {
      vel_[i] = cmd_[i];
      pos_[i] += cmd_[i] * dt;
    }
  }

private:
  double pos_[4] = { 0, 0, 0, 0 }, vel_[4] = { 0, 0, 0, 0 }, eff_[4] = { 0, 0, 0, 0 }, cmd_[4] = { 0, 0, 0, 0 };
  hardware_interface::JointStateInterface state_;
  hardware_interface::VelocityJointInterface velocity_;
};

void setParams(const std::string& ns)
{
  ros::param::set(ns + "/joint_state_controller/type", std::string("joint_state_controller/JointStateController"));
  ros::param::set(ns + "/joint_state_controller/publish_rate", 50.0);
  const std::string d = ns + "/diffbot_controller/";
  ros::param::set(d + "type", std::string("diff_drive_controller/DiffDriveController"));
  ros::param::set(d + "left_wheel", std::vector<std::string>{ "wheel_1_joint", "wheel_3_joint" });
  ros::param::set(d + "right_wheel", std::vector<std::string>{ "wheel_2_joint", "wheel_4_joint" });
  ros::param::set(d + "wheel_separation", 0.182);
  ros::param::set(d + "wheel_radius", 0.0325);
  ros::param::set(d + "publish_rate", 50.0);
  ros::param::set(d + "cmd_vel_timeout", 0.5);
  const std::vector<double> cov{ 0.001, 0.001, 1e6, 1e6, 1e6, 1000.0 };
  ros::param::set(d + "pose_covariance_diagonal", cov);
  ros::param::set(d + "twist_covariance_diagonal", cov);
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "control_loop_bench");
  const int updates = argc > 1 ? std::atoi(argv[1]) : 20000;
  const std::string ns = "/control_loop_bench";
  setParams(ns);
  ros::NodeHandle nh(ns);
  FourWheels hw;
  controller_manager::ControllerManager cm(&hw, nh);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const ros::Duration period(0.001);

  for (const char* name : { "joint_state_controller", "diffbot_controller" })
  {
    if (!cm.loadController(name))
    {
      ROS_FATAL("control_loop_bench: could not load %s", name);
      return 1;
    }
  }
  bool switched = false;
  std::thread sw([&] { switched = cm.switchController({ "joint_state_controller", "diffbot_controller" }, {}, 2); });
  while (!switched && sw.joinable())
  {
    cm.update(ros::Time::now(), period);
    ros::WallDuration(0.001).sleep();
    if (switched)
      break;
    static int spins = 0;
    if (++spins > 20000)
      break;
  }
  sw.join();
  if (!switched)
  {
    ROS_FATAL("control_loop_bench: the controllers did not start");
    return 1;
  }
  ros::Publisher cmd = nh.advertise<geometry_msgs::Twist>("diffbot_controller/cmd_vel", 1);
  geometry_msgs::Twist twist;
  twist.linear.x = 0.3;
  twist.angular.z = 0.5;

  std::vector<double> us;
  us.reserve(updates);
  for (int k = 0; k < updates; ++k)
  {
    if (k % 20 == 0)
      cmd.publish(twist);  // 50 Hz of commands, as a teleop or move_base would send
    hw.step(period.toSec());
    const ros::Time now = ros::Time::now();
    const auto t0 = std::chrono::steady_clock::now();
    cm.update(now, period);
    const auto t1 = std::chrono::steady_clock::now();
    us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // let the publisher threads run
  }
  std::vector<double> sorted = us;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0.0;
  for (double v : us)
    sum += v;
  const double mean = sum / us.size();
  const double p99 = sorted[static_cast<std::size_t>(0.99 * (sorted.size() - 1))];
  printf(
      "control_loop: ControllerManager::update, 4 joints, joint_state_controller + diff_drive_controller, %d updates\n",
      updates);
  printf("  mean %.2f us, p99 %.2f us, max %.2f us\n", mean, p99, sorted.back());
  printf("  mean / 1 kHz period: %.4f (target <= 0.02): %s; p99 / period %.4f\n", mean / 1000.0,
         mean / 1000.0 <= 0.02 ? "OK" : "ABOVE TARGET", p99 / 1000.0);
  spinner.stop();
  return 0;
}
