// rosserial client library (re-implementation): tf::TransformBroadcaster, tf/tfMessage on /tf.
#ifndef ROS_TRANSFORM_BROADCASTER_H_
#define ROS_TRANSFORM_BROADCASTER_H_

#include "ros.h"
#include "tf/tfMessage.h"

namespace tf
{

class TransformBroadcaster
{
public:
  TransformBroadcaster() : publisher_("/tf", &internal_msg) {}

  void init(ros::NodeHandle &nh) { nh.advertise(publisher_); }

  void sendTransform(geometry_msgs::TransformStamped &transform)
  {
    internal_msg.transforms_length = 1;
    internal_msg.transforms = &transform;
    publisher_.publish(&internal_msg);
    internal_msg.transforms_length = 0;
    internal_msg.transforms = 0;
  }

private:
  tf::tfMessage internal_msg;
  ros::Publisher publisher_;
};

}  // namespace tf

#endif
