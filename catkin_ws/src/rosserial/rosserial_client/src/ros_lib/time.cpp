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
  int32_t s = t / 1000000000L;
  int32_t ns = t % 1000000000L;
  normalizeSecNSecSigned(s, ns);
  sec = (uint32_t)s;
  nsec = (uint32_t)ns;
  return *this;
}

// Unsigned arithmetic: seconds wrap modulo 2^32 (0 - 0.5 s = 4294967295.5 s), as the original.
Time &Time::operator+=(const Duration &rhs)
{
  // nsec, rhs.nsec are in [0, 1e9): borrowing one second keeps the sum positive and < 2^32
  sec = sec - 1UL + (uint32_t)rhs.sec;
  nsec = nsec + 1000000000UL + (uint32_t)rhs.nsec;
  normalizeSecNSec(sec, nsec);
  return *this;
}

Time &Time::operator-=(const Duration &rhs)
{
  sec = sec - 1UL - (uint32_t)rhs.sec;
  nsec = nsec + 1000000000UL - (uint32_t)rhs.nsec;
  normalizeSecNSec(sec, nsec);
  return *this;
}
}  // namespace ros
