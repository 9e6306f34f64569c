// rosserial_server udp_socket_node: one rosserial device over UDP (a Wi-Fi board that sends
// datagrams), as the original's node:
//   rosrun rosserial_server udp_socket_node _server_port:=11411 _client_port:=11411
//          _client_addr:=192.168.1.50
// The node binds ~server_port and talks to ~client_addr:~client_port; each datagram carries
// whole frames. While the client is not listening (ICMP port unreachable) the session keeps
// asking for its topics, as the original.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <ros/ros.h>

#include "rosserial_server/msg_lookup.h"
#include "rosserial_server/session.h"
#include "rosserial_server/stream.h"

namespace
{

bool validPort(int port, const char* name)
{
  if (port > 0 && port <= 65535)
    return true;
  ROS_FATAL("~%s: %d is not a UDP port (1..65535)", name, port);
  return false;
}

// A UDP socket bound to server_port and connected to the client; -1 with a FATAL line.
int openUdp(int server_port, const sockaddr_in& client)
{
  int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in addr;
  std::memset(&addr, 0, sizeof(addr));
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  addr.sin_port = htons((uint16_t)server_port);
  if (::bind(fd, (sockaddr*)&addr, sizeof(addr)) != 0 || ::connect(fd, (const sockaddr*)&client, sizeof(client)) != 0)
  {
    ROS_FATAL("Cannot use UDP port %d towards the client: %s", server_port, std::strerror(errno));
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace

int main(int argc, char** argv)
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  ros::init(argc, argv, "rosserial_server_udp_socket_node");
  ros::NodeHandle pnh("~");
  ros::NodeHandle nh;
  int server_port, client_port;
  std::string client_addr;
  double sync_timeout;
  pnh.param<int>("server_port", server_port, 11411);
  pnh.param<int>("client_port", client_port, 11411);
  pnh.param<std::string>("client_addr", client_addr, "127.0.0.1");
  pnh.param<double>("sync_timeout", sync_timeout, 15.0);
  if (!validPort(server_port, "server_port") || !validPort(client_port, "client_port"))
    return 1;
  sockaddr_in client;
  std::memset(&client, 0, sizeof(client));
  client.sin_family = AF_INET;
  client.sin_port = htons((uint16_t)client_port);
  if (inet_pton(AF_INET, client_addr.c_str(), &client.sin_addr) != 1)
  {
    ROS_FATAL("~client_addr: '%s' is not an IPv4 address", client_addr.c_str());
    return 1;
  }
  rosserial_server::warmUpLookups();
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ROS_INFO("rosserial UDP session on port %d with %s:%d", server_port, client_addr.c_str(), client_port);
  while (ros::ok())
  {
    const int fd = openUdp(server_port, client);
    if (fd < 0)
      return 1;
    auto stream = std::make_shared<rosserial_server::FdStream>(fd, client_addr + ":" + std::to_string(client_port));
    rosserial_server::Session session(nh, stream);
    session.setSyncTimeout(sync_timeout);
    session.run([] { return ros::ok(); });
    if (ros::ok())
      ros::WallDuration(0.5).sleep();  // the socket failed: start over
  }
  spinner.stop();
  return 0;
}
