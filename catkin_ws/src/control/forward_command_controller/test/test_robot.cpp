// Test hardware for the controller packages' rostests: a RobotHW with simulated joints,
// stepping a fixed period on its own clock (published on /clock; run with use_sim_time) in a
// loop thread `read(); cm.update(t, dt); write();`, callbacks served by an AsyncSpinner.
//
// Private parameters:
//   ~joints: list of {name, interface: effort|velocity|position|state, position: initial [rad]}
//   ~period: control period [s] (0.01); ~inertia [kg m^2] (1.0) and ~damping [N m s/rad] (0.0)
//   of effort joints; ~realtime_factor: sim seconds per wall second (2.0).
#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include <controller_manager/controller_manager.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

namespace
{

struct Joint
{
  std::string name;
  std::string interface;
  double pos = 0.0;
  double vel = 0.0;
  double eff = 0.0;
  double cmd = 0.0;
};

class TestRobot : public hardware_interface::RobotHW
{
public:
  bool configure(ros::NodeHandle& pnh)
  {
    pnh.param("inertia", inertia_, 1.0);
    pnh.param("damping", damping_, 0.0);
    XmlRpc::XmlRpcValue list;
    if (!pnh.getParam("joints", list) || list.getType() != XmlRpc::XmlRpcValue::TypeArray)
    {
      ROS_ERROR("test_robot: ~joints must be a list of {name, interface}");
      return false;
    }
    joints_.resize(list.size());
    for (int i = 0; i < list.size(); ++i)
    {
      Joint& j = joints_[i];
      j.name = static_cast<std::string>(list[i]["name"]);
      j.interface = list[i].hasMember("interface") ? static_cast<std::string>(list[i]["interface"]) : "effort";
      if (list[i].hasMember("position"))
        j.pos = list[i]["position"].getType() == XmlRpc::XmlRpcValue::TypeInt
                    ? static_cast<int>(list[i]["position"])
                    : static_cast<double>(list[i]["position"]);
      j.cmd = j.interface == "position" ? j.pos : 0.0;
    }
    for (Joint& j : joints_)
    {
      hardware_interface::JointStateHandle state(j.name, &j.pos, &j.vel, &j.eff);
      state_interface_.registerHandle(state);
      if (j.interface == "effort")
        effort_interface_.registerHandle(hardware_interface::JointHandle(state, &j.cmd));
      else if (j.interface == "velocity")
        velocity_interface_.registerHandle(hardware_interface::JointHandle(state, &j.cmd));
      else if (j.interface == "position")
        position_interface_.registerHandle(hardware_interface::JointHandle(state, &j.cmd));
      else if (j.interface != "state")
      {
        ROS_ERROR("test_robot: joint '%s' has unknown interface '%s'", j.name.c_str(), j.interface.c_str());
        return false;
      }
    }
    registerInterface(&state_interface_);
    registerInterface(&effort_interface_);
    registerInterface(&velocity_interface_);
    registerInterface(&position_interface_);
    return true;
  }

  /// Simple physics of one period dt [s].
  void write(const ros::Time& /*time*/, const ros::Duration& period) override
  {
    const double dt = period.toSec();
    for (Joint& j : joints_)
    {
      if (j.interface == "effort")
      {
        j.eff = j.cmd;
        const double acc = (j.cmd - damping_ * j.vel) / inertia_;
        j.vel += acc * dt;  // semi-implicit Euler
        j.pos += j.vel * dt;
      }
      else if (j.interface == "velocity")
      {
        j.vel = j.cmd;
        j.pos += j.vel * dt;
      }
      else if (j.interface == "position")
      {
        j.vel = (j.cmd - j.pos) / dt;
        j.pos = j.cmd;
      }
    }
  }

private:
  std::vector<Joint> joints_;
  double inertia_ = 1.0;
  double damping_ = 0.0;
  hardware_interface::JointStateInterface state_interface_;
  hardware_interface::EffortJointInterface effort_interface_;
  hardware_interface::VelocityJointInterface velocity_interface_;
  hardware_interface::PositionJointInterface position_interface_;
};

}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "test_robot");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");

  TestRobot robot;
  if (!robot.configure(pnh))
    return 1;
  double period_s = 0.01, realtime_factor = 2.0;
  pnh.param("period", period_s, 0.01);
  pnh.param("realtime_factor", realtime_factor, 2.0);

  controller_manager::ControllerManager cm(&robot, nh);
  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 1);

  ros::AsyncSpinner spinner(2);
  spinner.start();

  std::atomic<bool> running(true);
  std::thread loop(
      [&]
      {
        const ros::Duration period(period_s);
        ros::Time time(0.0);
        ros::WallRate rate(realtime_factor / period_s);
        while (running && ros::ok())
        {
          time += period;
          rosgraph_msgs::Clock clock;
          clock.clock = time;
          clock_pub.publish(clock);
          robot.read(time, period);
          cm.update(time, period);
          robot.write(time, period);
          rate.sleep();
        }
      });
  ros::waitForShutdown();
  running = false;
  loop.join();
  return 0;
}
