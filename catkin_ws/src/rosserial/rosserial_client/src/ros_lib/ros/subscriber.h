// rosserial client library (re-implementation): ros::Subscriber<MsgT[, ObjT]>.
#ifndef ROS_SUBSCRIBER_H_
#define ROS_SUBSCRIBER_H_

#include "rosserial_msgs/TopicInfo.h"

namespace ros
{

// What the node handle sees of any subscriber (also of service servers and clients).
class Subscriber_
{
public:
  virtual ~Subscriber_() {}
  virtual void callback(unsigned char *data) = 0;
  virtual int getEndpointType() = 0;
  virtual const char *getMsgType() = 0;
  virtual const char *getMsgMD5() = 0;
  int id_;
  const char *topic_;
};

// A subscriber calling a member function of obj.
template <typename MsgT, typename ObjT = void>
class Subscriber : public Subscriber_
{
public:
  typedef void (ObjT::*CallbackT)(const MsgT &);

  Subscriber(const char *topic_name, CallbackT cb, ObjT *obj, int endpoint = rosserial_msgs::TopicInfo::ID_SUBSCRIBER)
    : cb_(cb), obj_(obj), endpoint_(endpoint)
  {
    topic_ = topic_name;
  }

  virtual void callback(unsigned char *data) override
  {
    msg.deserialize(data);
    (obj_->*cb_)(msg);
  }
  virtual const char *getMsgType() override { return msg.getType(); }
  virtual const char *getMsgMD5() override { return msg.getMD5(); }
  virtual int getEndpointType() override { return endpoint_; }

  MsgT msg;

private:
  CallbackT cb_;
  ObjT *obj_;
  int endpoint_;
};

// A subscriber calling a free function.
template <typename MsgT>
class Subscriber<MsgT, void> : public Subscriber_
{
public:
  typedef void (*CallbackT)(const MsgT &);

  Subscriber(const char *topic_name, CallbackT cb, int endpoint = rosserial_msgs::TopicInfo::ID_SUBSCRIBER)
    : cb_(cb), endpoint_(endpoint)
  {
    topic_ = topic_name;
  }

  virtual void callback(unsigned char *data) override
  {
    msg.deserialize(data);
    this->cb_(msg);
  }
  virtual const char *getMsgType() override { return msg.getType(); }
  virtual const char *getMsgMD5() override { return msg.getMD5(); }
  virtual int getEndpointType() override { return endpoint_; }

  MsgT msg;

private:
  CallbackT cb_;
  int endpoint_;
};

}  // namespace ros

#endif
