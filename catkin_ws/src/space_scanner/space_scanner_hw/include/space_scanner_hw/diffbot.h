// The diploma's high level (section 2.5, figures 2.18-2.22): class Diffbot, a
// hardware_interface::RobotHW for the 4-wheel space scanner, reconstructed from the printed
// code. Joints wheel_0_joint ... wheel_<N-1>_joint (0 and 2 left, 1 and 3 right) with a
// JointStateInterface and a VelocityJointInterface; the Arduino's measured wheel speeds come in
// on motor_left_vel / motor_right_vel (std_msgs/Float64), the commands go out on
// motor_left_cmd / motor_right_cmd (std_msgs/Int32) when they change; services start / stop.
// Parts the scan does not show (template header, getTime/getPeriod, the service callbacks) follow
// the template the diploma names as its model [45]; see README.md for every guessed reading.
#pragma once

#include <algorithm>
#include <limits>
#include <sstream>

#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>
#include <std_srvs/Empty.h>

template <unsigned int NUM_JOINTS = 2>
class Diffbot : public hardware_interface::RobotHW
{
public:
  Diffbot()
    : running_(true)
    , start_srv_(nh_.advertiseService("start", &Diffbot::start_callback, this))
    , stop_srv_(nh_.advertiseService("stop", &Diffbot::stop_callback, this))
  {
    // Intialize raw data
    std::fill_n(pos_, NUM_JOINTS, 0.0);
    std::fill_n(vel_, NUM_JOINTS, 0.0);
    std::fill_n(eff_, NUM_JOINTS, 0.0);
    std::fill_n(cmd_, NUM_JOINTS, 0.0);

    // Connect and register the joint state and velocity interface
    for (unsigned int i = 0; i < NUM_JOINTS; ++i)
    {
      std::ostringstream os;
      os << "wheel_" << i << "_joint";

      hardware_interface::JointStateHandle state_handle(os.str(), &pos_[i], &vel_[i], &eff_[i]);
      jnt_state_interface_.registerHandle(state_handle);

      hardware_interface::JointHandle vel_handle(jnt_state_interface_.getHandle(os.str()), &cmd_[i]);
      jnt_vel_interface_.registerHandle(vel_handle);
    }

    registerInterface(&jnt_state_interface_);
    registerInterface(&jnt_vel_interface_);
  }

  ros::Time getTime() const { return ros::Time::now(); }
  ros::Duration getPeriod() const { return ros::Duration(0.01); }

  void leftMotorCallback(const std_msgs::Float64::ConstPtr& msg)
  {
    vel_[0] = msg->data;
    vel_[2] = vel_[0];
    // ROS_WARN_STREAM("Commands for joints: " <<vel_[0]);
  }

  void rightMotorCallback(const std_msgs::Float64::ConstPtr& msg)
  {
    vel_[1] = msg->data;
    vel_[3] = vel_[1];
    // ROS_WARN_STREAM("Commands for joints: " <<vel_[1]);
  }

  void init(ros::NodeHandle& nh)
  {
    nh_ = nh;
    pub_left_motor_value_ = nh_.advertise<std_msgs::Int32>("motor_left_cmd", 10);
    pub_right_motor_value_ = nh_.advertise<std_msgs::Int32>("motor_right_cmd", 10);
    sub_left_motor_vel_ = nh_.subscribe("motor_left_vel", 10, &Diffbot::leftMotorCallback, this);
    sub_right_motor_vel_ = nh_.subscribe("motor_right_vel", 10, &Diffbot::rightMotorCallback, this);
    ROS_INFO_STREAM("init completed");
  }

  void read()
  {
    // Read the joint state of the robot into the hardware interface
    if (running_)
    {
      for (unsigned int i = 0; i < NUM_JOINTS; ++i)
      {
        // Note that pos_[i] will be NaN for one more cycle after we start(),
        // but that is consistent with the knowledge we have about the state
        // of the robot.
        pos_[i] += vel_[i] * getPeriod().toSec();  // update position
        // vel_[i] = cmd_[i]; // might add smoothing here later
      }
    }
    else
    {
      std::fill_n(pos_, NUM_JOINTS, std::numeric_limits<double>::quiet_NaN());
      std::fill_n(vel_, NUM_JOINTS, std::numeric_limits<double>::quiet_NaN());
    }
  }

  void write()
  {
    // // Write the commands to the joints
    // std::ostringstream os;
    // for (unsigned int i = 0; i < NUM_JOINTS - 1; ++i)
    // {
    //   os << vel_[i] << ", ";
    // }
    // os << vel_[NUM_JOINTS - 1];

    // ROS_WARN_STREAM("Commands for vel: " << os.str());

    if (cmd_[0] != lcmd.data || cmd_[1] != rcmd.data)
    {
      lcmd.data = cmd_[0];
      rcmd.data = cmd_[1];
      pub_left_motor_value_.publish(lcmd);
      pub_right_motor_value_.publish(rcmd);
    }
  }

  bool start_callback(std_srvs::Empty::Request& /*req*/, std_srvs::Empty::Response& /*res*/)
  {
    running_ = true;
    return true;
  }

  bool stop_callback(std_srvs::Empty::Request& /*req*/, std_srvs::Empty::Response& /*res*/)
  {
    running_ = false;
    return true;
  }

private:
  hardware_interface::JointStateInterface jnt_state_interface_;
  hardware_interface::VelocityJointInterface jnt_vel_interface_;
  double cmd_[NUM_JOINTS];
  double pos_[NUM_JOINTS];
  double vel_[NUM_JOINTS];
  double eff_[NUM_JOINTS];

  bool running_;

  ros::NodeHandle nh_;
  ros::ServiceServer start_srv_;
  ros::ServiceServer stop_srv_;

  ros::Publisher pub_left_motor_value_;
  ros::Publisher pub_right_motor_value_;
  ros::Subscriber sub_left_motor_vel_;
  ros::Subscriber sub_right_motor_vel_;
  std_msgs::Int32 rcmd;
  std_msgs::Int32 lcmd;
};
