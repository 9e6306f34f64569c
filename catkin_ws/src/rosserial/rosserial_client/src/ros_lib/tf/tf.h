// rosserial client library (re-implementation): quaternion helper of the original tf/tf.h.
#ifndef ROS_TF_H_
#define ROS_TF_H_

#include <math.h>
#include "geometry_msgs/Quaternion.h"

namespace tf
{
static inline geometry_msgs::Quaternion createQuaternionFromYaw(double yaw)
{
  geometry_msgs::Quaternion q;
  q.x = 0;
  q.y = 0;
  q.z = sin(yaw * 0.5);
  q.w = cos(yaw * 0.5);
  return q;
}
}  // namespace tf

#endif
