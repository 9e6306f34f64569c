// rosserial_server socket_node: rosserial devices over TCP (ESP8266/ESP32 boards, Wi-Fi).
//   rosrun rosserial_server socket_node _port:=11411
// Every accepted connection is its own session, served beside the others.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <list>
#include <memory>
#include <thread>

#include <ros/ros.h>

#include "rosserial_server/msg_lookup.h"
#include "rosserial_server/session.h"
#include "rosserial_server/stream.h"

int main(int argc, char** argv)
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // log lines reach a redirected stdout at once
  ros::init(argc, argv, "rosserial_server_socket_node");
  ros::NodeHandle pnh("~");
  ros::NodeHandle nh;
  int port;
  pnh.param<int>("port", port, 11411);
  double sync_timeout;
  pnh.param<double>("sync_timeout", sync_timeout, 15.0);
  if (port <= 0 || port > 65535)
  {
    ROS_FATAL("~port: %d is not a TCP port (1..65535)", port);
    return 1;
  }

  int server = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  int one = 1;
  ::setsockopt(server, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in addr;
  std::memset(&addr, 0, sizeof(addr));
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  addr.sin_port = htons((uint16_t)port);
  if (::bind(server, (sockaddr*)&addr, sizeof(addr)) != 0 || ::listen(server, 8) != 0)
  {
    ROS_FATAL("Cannot listen on TCP port %d: %s", port, std::strerror(errno));
    return 1;
  }
  std::cout << "Listening on port " << port << std::endl;
  ROS_INFO("Listening for rosserial TCP connections on port %d", port);

  rosserial_server::warmUpLookups();
  ros::AsyncSpinner spinner(2);
  spinner.start();

  std::list<std::thread> sessions;
  while (ros::ok())
  {
    pollfd p{ server, POLLIN, 0 };
    if (::poll(&p, 1, 200) <= 0)
      continue;
    sockaddr_in peer;
    socklen_t len = sizeof(peer);
    int fd = ::accept4(server, (sockaddr*)&peer, &len, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0)
      continue;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
    char host[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &peer.sin_addr, host, sizeof(host));
    const std::string name = std::string(host) + ":" + std::to_string(ntohs(peer.sin_port));
    ROS_INFO("Established a socket connection from %s", name.c_str());
    auto stream = std::make_shared<rosserial_server::FdStream>(fd, name);
    sessions.emplace_back(
        [nh, stream, sync_timeout]()
        {
          rosserial_server::Session session(nh, stream);
          session.setSyncTimeout(sync_timeout);
          session.run([] { return ros::ok(); });
        });
  }
  ::close(server);
  for (auto& t : sessions)
    t.join();
  spinner.stop();
  return 0;
}
