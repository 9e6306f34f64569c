// rosserial client library (re-implementation): ros::Time.
#ifndef ROS_TIME_H_
#define ROS_TIME_H_

#include <stdint.h>
#include "ros/duration.h"

namespace ros
{
void normalizeSecNSec(uint32_t &sec, uint32_t &nsec);

class Time
{
public:
  uint32_t sec, nsec;

  Time() : sec(0), nsec(0) {}
  Time(uint32_t _sec, uint32_t _nsec) : sec(_sec), nsec(_nsec)
  {
    normalizeSecNSec(sec, nsec);
  }

  double toSec() const { return (double)sec + 1e-9 * (double)nsec; }
  void fromSec(double t)
  {
    sec = (uint32_t)t;
    nsec = (uint32_t)((t - sec) * 1e9);
  }
  uint32_t toNsec() { return (uint32_t)sec * 1000000000UL + nsec; }
  Time &fromNSec(int32_t t);

  Time &operator+=(const Duration &rhs);
  Time &operator-=(const Duration &rhs);

};

}  // namespace ros

#endif
