// rosserial client library (re-implementation): ros::ServiceClient<MReq, MRes>, the device
// calling a ROS service.
#ifndef ROS_SERVICE_CLIENT_H_
#define ROS_SERVICE_CLIENT_H_

#include "rosserial_msgs/TopicInfo.h"
#include "ros/publisher.h"
#include "ros/subscriber.h"

namespace ros
{

template <typename MReq, typename MRes>
class ServiceClient : public Subscriber_
{
public:
  ServiceClient(const char *topic_name)
    : pub(topic_name, &req, rosserial_msgs::TopicInfo::ID_SERVICE_CLIENT + rosserial_msgs::TopicInfo::ID_PUBLISHER)
    , ret(0)
    , waiting(false)
  {
    this->topic_ = topic_name;
  }

  // Blocks (spinning the node handle) until the response arrives or the link drops.
  void call(const MReq &request, MRes &response)
  {
    if (!pub.nh_ || !pub.nh_->connected())
      return;
    ret = &response;
    waiting = true;
    pub.publish(&request);
    while (waiting)
    {
      if (pub.nh_->spinOnce() < 0 || !pub.nh_->connected())
        break;
    }
    ret = 0;
  }

  virtual void callback(unsigned char *data) override
  {
    if (ret)
      ret->deserialize(data);
    waiting = false;
  }
  virtual const char *getMsgType() override { return this->resp.getType(); }
  virtual const char *getMsgMD5() override { return this->resp.getMD5(); }
  virtual int getEndpointType() override
  {
    return rosserial_msgs::TopicInfo::ID_SERVICE_CLIENT + rosserial_msgs::TopicInfo::ID_SUBSCRIBER;
  }

  MReq req;
  MRes resp;
  Publisher pub;

private:
  MRes *ret;
  bool waiting;
};

}  // namespace ros

#endif
