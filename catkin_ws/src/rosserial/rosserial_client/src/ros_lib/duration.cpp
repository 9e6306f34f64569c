// rosserial client library (re-implementation): ros::Duration arithmetic.
#include "ros/duration.h"

namespace ros
{
void normalizeSecNSecSigned(int32_t &sec, int32_t &nsec)
{
  int32_t nsec_part = nsec % 1000000000L;
  int32_t sec_part = sec + nsec / 1000000000L;
  if (nsec_part < 0)
  {
    nsec_part += 1000000000L;
    --sec_part;
  }
  sec = sec_part;
  nsec = nsec_part;
}

Duration &Duration::operator+=(const Duration &rhs)
{
  sec += rhs.sec;
  nsec += rhs.nsec;  // both < 1e9: no overflow
  normalizeSecNSecSigned(sec, nsec);
  return *this;
}

Duration &Duration::operator-=(const Duration &rhs)
{
  sec -= rhs.sec;
  nsec -= rhs.nsec;
  normalizeSecNSecSigned(sec, nsec);
  return *this;
}

Duration &Duration::operator*=(double scale)
{
  fromSec(toSec() * scale);
  return *this;
}
}  // namespace ros
