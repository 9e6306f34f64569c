// rosserial client library (re-implementation): ros::ServiceServer<MReq, MRes[, ObjT]>, a
// service served by the device.
#ifndef ROS_SERVICE_SERVER_H_
#define ROS_SERVICE_SERVER_H_

#include "rosserial_msgs/TopicInfo.h"
#include "ros/publisher.h"
#include "ros/subscriber.h"

namespace ros
{

template <typename MReq, typename MRes, typename ObjT = void>
class ServiceServer : public Subscriber_
{
public:
  typedef void (ObjT::*CallbackT)(const MReq &, MRes &);

  ServiceServer(const char *topic_name, CallbackT cb, ObjT *obj)
    : pub(topic_name, &resp, rosserial_msgs::TopicInfo::ID_SERVICE_SERVER + rosserial_msgs::TopicInfo::ID_PUBLISHER)
    , obj_(obj)
    , cb_(cb)
  {
    this->topic_ = topic_name;
  }

  virtual void callback(unsigned char *data) override
  {
    req.deserialize(data);
    (obj_->*cb_)(req, resp);
    pub.publish(&resp);
  }
  virtual const char *getMsgType() override { return this->req.getType(); }
  virtual const char *getMsgMD5() override { return this->req.getMD5(); }
  virtual int getEndpointType() override
  {
    return rosserial_msgs::TopicInfo::ID_SERVICE_SERVER + rosserial_msgs::TopicInfo::ID_SUBSCRIBER;
  }

  MReq req;
  MRes resp;
  Publisher pub;

private:
  ObjT *obj_;
  CallbackT cb_;
};

template <typename MReq, typename MRes>
class ServiceServer<MReq, MRes, void> : public Subscriber_
{
public:
  typedef void (*CallbackT)(const MReq &, MRes &);

  ServiceServer(const char *topic_name, CallbackT cb)
    : pub(topic_name, &resp, rosserial_msgs::TopicInfo::ID_SERVICE_SERVER + rosserial_msgs::TopicInfo::ID_PUBLISHER)
    , cb_(cb)
  {
    this->topic_ = topic_name;
  }

  virtual void callback(unsigned char *data) override
  {
    req.deserialize(data);
    cb_(req, resp);
    pub.publish(&resp);
  }
  virtual const char *getMsgType() override { return this->req.getType(); }
  virtual const char *getMsgMD5() override { return this->req.getMD5(); }
  virtual int getEndpointType() override
  {
    return rosserial_msgs::TopicInfo::ID_SERVICE_SERVER + rosserial_msgs::TopicInfo::ID_SUBSCRIBER;
  }

  MReq req;
  MRes resp;
  Publisher pub;

private:
  CallbackT cb_;
};

}  // namespace ros

#endif
