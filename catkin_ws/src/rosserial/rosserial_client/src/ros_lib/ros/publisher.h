// rosserial client library (re-implementation): ros::Publisher.
#ifndef ROS_PUBLISHER_H_
#define ROS_PUBLISHER_H_

#include "rosserial_msgs/TopicInfo.h"
#include "ros/node_handle_base.h"

namespace ros
{

class Publisher
{
public:
  Publisher(const char *topic_name, Msg *msg, int endpoint = rosserial_msgs::TopicInfo::ID_PUBLISHER)
    : topic_(topic_name), msg_(msg), id_(0), nh_(0), endpoint_(endpoint)
  {
  }

  int publish(const Msg *msg)
  {
    if (nh_ == 0)
      return -1;  // not advertised
    return nh_->publish(id_, msg);
  }
  int getEndpointType() { return endpoint_; }

  const char *topic_;
  Msg *msg_;
  int id_;
  NodeHandleBase_ *nh_;

private:
  int endpoint_;
};

}  // namespace ros

#endif
