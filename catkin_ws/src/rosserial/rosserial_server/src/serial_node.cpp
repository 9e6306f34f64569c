// rosserial_server serial_node: a rosserial device on a serial port (or pty).
//   rosrun rosserial_server serial_node _port:=/dev/ttyACM0 _baud:=57600
// The port is (re)opened every 0.2 s until it exists; when it vanishes (USB unplugged, the pty's
// other side closed) the session ends and the port is opened again.
#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>

#include <ros/ros.h>

#include "rosserial_server/msg_lookup.h"
#include "rosserial_server/session.h"
#include "rosserial_server/stream.h"

int main(int argc, char** argv)
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // log lines reach a redirected stdout at once
  ros::init(argc, argv, "rosserial_server_serial_node");
  ros::NodeHandle pnh("~");
  ros::NodeHandle nh;
  std::string port;
  int baud;
  pnh.param<std::string>("port", port, "/dev/ttyACM0");
  pnh.param<int>("baud", baud, 57600);
  double sync_timeout;
  pnh.param<double>("sync_timeout", sync_timeout, 15.0);

  rosserial_server::warmUpLookups();
  ros::AsyncSpinner spinner(2);  // subscriptions and service calls beside the read loop
  spinner.start();

  bool announced = false;
  while (ros::ok())
  {
    std::string error;
    int fd = rosserial_server::openSerial(port, baud, error);
    if (fd < 0)
    {
      if (!announced)
        ROS_WARN("Unable to open port %s: %s (retrying)", port.c_str(), error.c_str());
      announced = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      continue;
    }
    announced = false;
    ROS_INFO("Opened serial port %s at %d baud", port.c_str(), baud);
    auto stream = std::make_shared<rosserial_server::FdStream>(fd, port);
    {
      rosserial_server::Session session(nh, stream);
      session.setSyncTimeout(sync_timeout);
      session.run([] { return ros::ok(); });
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  spinner.stop();
  return 0;
}
