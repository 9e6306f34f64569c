// The test harness's client hardware, as the original rosserial_test's: the generated
// ros_lib included inside `namespace rosserial`, talking over a file descriptor the test sets.
#ifndef HARNESS_CLIENT_ROS_H
#define HARNESS_CLIENT_ROS_H

#include "rosserial/ros/node_handle.h"
#include "rosserial/duration.cpp"
#include "rosserial/time.cpp"

class ClientComms
{
public:
  static int fd;
  void init() {}
  int read()
  {
    unsigned char ch;
    return ::read(fd, &ch, 1) == 1 ? ch : -1;
  }
  void write(uint8_t* data, int length)
  {
    int done = 0;
    while (done < length)
    {
      ssize_t n = ::write(fd, data + done, length - done);
      if (n > 0)
        done += n;
    }
  }
  unsigned long time()
  {
    timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1000UL + t.tv_nsec / 1000000UL;
  }
};
int ClientComms::fd = -1;

namespace ros
{
typedef NodeHandle_<ClientComms, 5, 5, 200, 200> NodeHandle;
}

#endif
