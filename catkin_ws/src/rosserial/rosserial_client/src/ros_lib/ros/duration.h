// rosserial client library (re-implementation): ros::Duration, signed seconds + nanoseconds,
// kept normalised (0 <= nsec < 1e9), with the arithmetic and comparisons of roscpp's Duration.
#ifndef ROS_DURATION_H_
#define ROS_DURATION_H_

#include <stdint.h>
#include <math.h>

namespace ros
{
void normalizeSecNSecSigned(int32_t &sec, int32_t &nsec);

class Duration
{
public:
  int32_t sec, nsec;

  Duration() : sec(0), nsec(0) {}
  Duration(int32_t _sec, int32_t _nsec) : sec(_sec), nsec(_nsec) { normalizeSecNSecSigned(sec, nsec); }
  explicit Duration(double t) : sec(0), nsec(0) { fromSec(t); }

  double toSec() const { return (double)sec + 1e-9 * (double)nsec; }
  void fromSec(double t)
  {
    const double s = floor(t);
    sec = (int32_t)s;
    nsec = (int32_t)round((t - s) * 1e9);
    normalizeSecNSecSigned(sec, nsec);
  }
  int64_t toNSec() const { return (int64_t)sec * 1000000000LL + (int64_t)nsec; }
  Duration &fromNSec(int64_t t)
  {
    sec = (int32_t)(t / 1000000000LL);
    nsec = (int32_t)(t % 1000000000LL);
    normalizeSecNSecSigned(sec, nsec);
    return *this;
  }
  bool isZero() const { return sec == 0 && nsec == 0; }

  Duration &operator+=(const Duration &rhs);
  Duration &operator-=(const Duration &rhs);
  Duration &operator*=(double scale);

  Duration operator+(const Duration &rhs) const
  {
    Duration d(*this);
    return d += rhs;
  }
  Duration operator-(const Duration &rhs) const
  {
    Duration d(*this);
    return d -= rhs;
  }
  Duration operator-() const
  {
    Duration d(*this);
    d.sec = -sec;
    d.nsec = -nsec;
    normalizeSecNSecSigned(d.sec, d.nsec);
    return d;
  }
  Duration operator*(double scale) const
  {
    Duration d(*this);
    return d *= scale;
  }

  bool operator==(const Duration &rhs) const { return sec == rhs.sec && nsec == rhs.nsec; }
  bool operator!=(const Duration &rhs) const { return !(*this == rhs); }
  bool operator<(const Duration &rhs) const { return sec < rhs.sec || (sec == rhs.sec && nsec < rhs.nsec); }
  bool operator>(const Duration &rhs) const { return rhs < *this; }
  bool operator<=(const Duration &rhs) const { return !(rhs < *this); }
  bool operator>=(const Duration &rhs) const { return !(*this < rhs); }
};

}  // namespace ros

#endif
