// rosserial client library (re-implementation): ros::Time arithmetic.
#include "ros/time.h"

namespace ros
{
void normalizeSecNSec(uint32_t &sec, uint32_t &nsec)
{
  sec += nsec / 1000000000UL;
  nsec = nsec % 1000000000UL;
}

Time &Time::fromNSec(int32_t t)
{
  sec = t / 1000000000L;
  nsec = t % 1000000000L;
  normalizeSecNSec(sec, nsec);
  return *this;
}

Time &Time::operator+=(const Duration &rhs)
{
  int32_t s = (int32_t)sec + rhs.sec;
  int32_t ns = (int32_t)nsec + rhs.nsec;
  normalizeSecNSecSigned(s, ns);
  sec = (uint32_t)s;
  nsec = (uint32_t)ns;
  return *this;
}

Time &Time::operator-=(const Duration &rhs)
{
  int32_t s = (int32_t)sec - rhs.sec;
  int32_t ns = (int32_t)nsec - rhs.nsec;
  normalizeSecNSecSigned(s, ns);
  sec = (uint32_t)s;
  nsec = (uint32_t)ns;
  return *this;
}
}  // namespace ros
