// rosserial client library (re-implementation): ros::Time, unsigned seconds + nanoseconds kept
// normalised (nsec < 1e9), with roscpp's arithmetic (Time - Time = Duration, Time +/- Duration,
// wrapping modulo 2^32 seconds as the original's unsigned arithmetic) and comparisons.
#ifndef ROS_TIME_H_
#define ROS_TIME_H_

#include <stdint.h>
#include <math.h>
#include "ros/duration.h"

namespace ros
{
void normalizeSecNSec(uint32_t &sec, uint32_t &nsec);

class Time
{
public:
  uint32_t sec, nsec;

  Time() : sec(0), nsec(0) {}
  Time(uint32_t _sec, uint32_t _nsec) : sec(_sec), nsec(_nsec) { normalizeSecNSec(sec, nsec); }
  explicit Time(double t) : sec(0), nsec(0) { fromSec(t); }

  double toSec() const { return (double)sec + 1e-9 * (double)nsec; }
  void fromSec(double t)
  {
    const double s = floor(t);
    sec = (uint32_t)s;
    nsec = (uint32_t)round((t - s) * 1e9);
    normalizeSecNSec(sec, nsec);
  }
  // As the original: nanoseconds in 32 bits (wraps after 4.29 s; use toSec() for more).
  uint32_t toNsec() { return (uint32_t)sec * 1000000000UL + (uint32_t)nsec; }
  uint64_t toNSec() const { return (uint64_t)sec * 1000000000ULL + (uint64_t)nsec; }
  Time &fromNSec(int32_t t);
  bool isZero() const { return sec == 0 && nsec == 0; }

  Time &operator+=(const Duration &rhs);
  Time &operator-=(const Duration &rhs);

  Time operator+(const Duration &rhs) const
  {
    Time t(*this);
    return t += rhs;
  }
  Time operator-(const Duration &rhs) const
  {
    Time t(*this);
    return t -= rhs;
  }
  Duration operator-(const Time &rhs) const
  {
    return Duration((int32_t)(sec - rhs.sec), (int32_t)nsec - (int32_t)rhs.nsec);
  }

  bool operator==(const Time &rhs) const { return sec == rhs.sec && nsec == rhs.nsec; }
  bool operator!=(const Time &rhs) const { return !(*this == rhs); }
  bool operator<(const Time &rhs) const { return sec < rhs.sec || (sec == rhs.sec && nsec < rhs.nsec); }
  bool operator>(const Time &rhs) const { return rhs < *this; }
  bool operator<=(const Time &rhs) const { return !(rhs < *this); }
  bool operator>=(const Time &rhs) const { return !(*this < rhs); }

  // Declared as the original's (no definition there either: the node handle's now() is the
  // clock of a ros_lib program).
  static Time now();
  static void setNow(Time &new_now);
};

inline Time operator+(const Duration &lhs, const Time &rhs) { return rhs + lhs; }

}  // namespace ros

#endif
