// rosserial client library (re-implementation): ros::Duration.
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
  Duration(int32_t _sec, int32_t _nsec) : sec(_sec), nsec(_nsec)
  {
    normalizeSecNSecSigned(sec, nsec);
  }

  double toSec() const { return (double)sec + 1e-9 * (double)nsec; }
  void fromSec(double t)
  {
    sec = (int32_t)t;
    nsec = (int32_t)((t - sec) * 1e9);
  }

  Duration &operator+=(const Duration &rhs);
  Duration &operator-=(const Duration &rhs);
  Duration &operator*=(double scale);
};

}  // namespace ros

#endif
