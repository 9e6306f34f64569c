// rosserial client library (re-implementation): ros::NodeHandle_, the device end of the
// rosserial protocol (rev 1). Frame: 0xFF 0xFE len_lo len_hi len_chk topic_lo topic_hi
// payload... data_chk; each checksum makes its bytes sum to 255 (mod 256).
#ifndef ROS_NODE_HANDLE_H_
#define ROS_NODE_HANDLE_H_

#include <stdint.h>

#include "std_msgs/Time.h"
#include "rosserial_msgs/TopicInfo.h"
#include "rosserial_msgs/Log.h"
#include "rosserial_msgs/RequestParam.h"

#include "ros/msg.h"
#include "ros/time.h"
#include "ros/node_handle_base.h"
#include "ros/publisher.h"
#include "ros/subscriber.h"
#include "ros/service_server.h"
#include "ros/service_client.h"

namespace ros
{

const int SPIN_OK = 0;
const int SPIN_ERR = -1;
const int SPIN_TIMEOUT = -2;

const uint8_t SYNC_SECONDS = 5;
const uint8_t MODE_FIRST_FF = 0;
// Frame parser states (after the first 0xFF).
const uint8_t MODE_PROTOCOL_VER = 1;
const uint8_t PROTOCOL_VER1 = 0xff;  // rev 0 (groovy and earlier)
const uint8_t PROTOCOL_VER2 = 0xfe;  // rev 1 (hydro and later)
const uint8_t PROTOCOL_VER = PROTOCOL_VER2;
const uint8_t MODE_SIZE_L = 2;
const uint8_t MODE_SIZE_H = 3;
const uint8_t MODE_SIZE_CHECKSUM = 4;
const uint8_t MODE_TOPIC_L = 5;
const uint8_t MODE_TOPIC_H = 6;
const uint8_t MODE_MESSAGE = 7;
const uint8_t MODE_MSG_CHECKSUM = 8;

const uint8_t SERIAL_MSG_TIMEOUT = 20;  // ms a frame may take after its first 0xFF

template <class Hardware, int MAX_SUBSCRIBERS = 25, int MAX_PUBLISHERS = 25, int INPUT_SIZE = 512,
          int OUTPUT_SIZE = 512>
class NodeHandle_ : public NodeHandleBase_
{
protected:
  Hardware hardware_;

  // time since the last sync, and the ROS time offset
  uint32_t rt_time;
  uint32_t sec_offset, nsec_offset;

  // frame parser state
  uint8_t message_in[INPUT_SIZE];
  uint8_t message_out[OUTPUT_SIZE];

  Publisher *publishers[MAX_PUBLISHERS];
  Subscriber_ *subscribers[MAX_SUBSCRIBERS];

  int mode_;
  int bytes_;
  int topic_;
  int index_;
  int checksum_;

  bool configured_;

  uint32_t last_sync_time;
  uint32_t last_sync_receive_time;
  uint32_t last_msg_timeout_time;

  uint32_t spin_timeout_;

  bool param_received;
  rosserial_msgs::RequestParamResponse req_param_resp;

public:
  NodeHandle_() : configured_(false), spin_timeout_(0)
  {
    for (int i = 0; i < MAX_PUBLISHERS; i++)
      publishers[i] = 0;
    for (int i = 0; i < MAX_SUBSCRIBERS; i++)
      subscribers[i] = 0;
    for (int i = 0; i < INPUT_SIZE; i++)
      message_in[i] = 0;
    for (int i = 0; i < OUTPUT_SIZE; i++)
      message_out[i] = 0;
    rt_time = sec_offset = nsec_offset = 0;
    mode_ = MODE_FIRST_FF;
    bytes_ = topic_ = index_ = checksum_ = 0;
    last_sync_time = last_sync_receive_time = last_msg_timeout_time = 0;
    param_received = false;
  }

  Hardware *getHardware() { return &hardware_; }

  void initNode()
  {
    hardware_.init();
    mode_ = MODE_FIRST_FF;
    bytes_ = 0;
    index_ = 0;
    topic_ = 0;
    // Tell a host that is already listening that we (re)started: an empty frame on topic 0.
    // Our serial_node answers with a topic request at once; the original host ignores it.
    writeFrame(rosserial_msgs::TopicInfo::ID_PUBLISHER, 0);
  }

  void initNode(char *portName)
  {
    hardware_.init(portName);
    mode_ = MODE_FIRST_FF;
    bytes_ = 0;
    index_ = 0;
    topic_ = 0;
  }

  // A spinOnce() that keeps receiving bytes for longer than `timeout` ms returns SPIN_TIMEOUT
  // (0 = never).
  void setSpinTimeout(const uint32_t &timeout) { spin_timeout_ = timeout; }

  virtual int spinOnce() override
  {
    const uint32_t c_time = hardware_.time();
    if ((c_time - last_sync_receive_time) > (SYNC_SECONDS * 2200UL))
      configured_ = false;

    // a frame that did not finish in time is dropped
    if (mode_ != MODE_FIRST_FF && c_time > last_msg_timeout_time)
      mode_ = MODE_FIRST_FF;

    while (true)
    {
      if (spin_timeout_ > 0 && (hardware_.time() - c_time) > spin_timeout_)
      {
        configured_ = false;
        return SPIN_TIMEOUT;
      }
      const int data = hardware_.read();
      if (data < 0)
        break;
      checksum_ += data;
      if (mode_ == MODE_MESSAGE)
      {
        message_in[index_++] = data;
        bytes_--;
        if (bytes_ == 0)
          mode_ = MODE_MSG_CHECKSUM;
      }
      else if (mode_ == MODE_FIRST_FF)
      {
        if (data == 0xff)
        {
          mode_++;
          last_msg_timeout_time = c_time + SERIAL_MSG_TIMEOUT;
        }
        else if (hardware_.time() - c_time > (SYNC_SECONDS * 1000UL))
        {
          configured_ = false;
          return SPIN_TIMEOUT;
        }
      }
      else if (mode_ == MODE_PROTOCOL_VER)
      {
        if (data == PROTOCOL_VER)
          mode_++;
        else
        {
          mode_ = MODE_FIRST_FF;
          if (!configured_)
            requestSyncTime();  // lets the host see our protocol version
        }
      }
      else if (mode_ == MODE_SIZE_L)
      {
        bytes_ = data;
        index_ = 0;
        mode_++;
        checksum_ = data;
      }
      else if (mode_ == MODE_SIZE_H)
      {
        bytes_ += data << 8;
        mode_++;
      }
      else if (mode_ == MODE_SIZE_CHECKSUM)
      {
        // the payload must fit the input buffer: never write past it
        if ((checksum_ % 256) == 255 && bytes_ <= INPUT_SIZE)
          mode_++;
        else
          mode_ = MODE_FIRST_FF;
      }
      else if (mode_ == MODE_TOPIC_L)
      {
        topic_ = data;
        mode_++;
        checksum_ = data;
      }
      else if (mode_ == MODE_TOPIC_H)
      {
        topic_ += data << 8;
        mode_ = MODE_MESSAGE;
        if (bytes_ == 0)
          mode_ = MODE_MSG_CHECKSUM;
      }
      else if (mode_ == MODE_MSG_CHECKSUM)
      {
        mode_ = MODE_FIRST_FF;
        if ((checksum_ % 256) == 255)
        {
          if (topic_ == rosserial_msgs::TopicInfo::ID_PUBLISHER)
          {
            requestSyncTime();
            negotiateTopics();
            last_sync_time = c_time;
            last_sync_receive_time = c_time;
            return SPIN_ERR;
          }
          else if (topic_ == rosserial_msgs::TopicInfo::ID_TIME)
          {
            syncTime(message_in);
          }
          else if (topic_ == rosserial_msgs::TopicInfo::ID_PARAMETER_REQUEST)
          {
            req_param_resp.deserialize(message_in);
            param_received = true;
          }
          else if (topic_ == rosserial_msgs::TopicInfo::ID_TX_STOP)
          {
            configured_ = false;
          }
          else if (topic_ >= 100 && topic_ - 100 < MAX_SUBSCRIBERS && subscribers[topic_ - 100])
          {
            subscribers[topic_ - 100]->callback(message_in);
          }
        }
      }
    }

    if (configured_ && ((c_time - last_sync_time) > (SYNC_SECONDS * 500UL)))
    {
      requestSyncTime();
      last_sync_time = c_time;
    }
    return SPIN_OK;
  }

  virtual bool connected() override { return configured_; }

  // -- time ----------------------------------------------------------------------------------

  void requestSyncTime()
  {
    std_msgs::Time t;
    publish(rosserial_msgs::TopicInfo::ID_TIME, &t);
    rt_time = hardware_.time();
  }

  void syncTime(uint8_t *data)
  {
    std_msgs::Time t;
    const uint32_t offset = hardware_.time() - rt_time;
    t.deserialize(data);
    t.data.sec += offset / 1000;
    t.data.nsec += (offset % 1000) * 1000000UL;
    this->setNow(t.data);
    last_sync_receive_time = hardware_.time();
  }

  Time now()
  {
    const uint32_t ms = hardware_.time();
    Time current_time;
    current_time.sec = ms / 1000 + sec_offset;
    current_time.nsec = (ms % 1000) * 1000000UL + nsec_offset;
    normalizeSecNSec(current_time.sec, current_time.nsec);
    return current_time;
  }

  void setNow(const Time &new_now)
  {
    const uint32_t ms = hardware_.time();
    sec_offset = new_now.sec - ms / 1000 - 1;
    nsec_offset = new_now.nsec - (ms % 1000) * 1000000UL + 1000000000UL;
    normalizeSecNSec(sec_offset, nsec_offset);
  }

  // -- registration --------------------------------------------------------------------------

  bool advertise(Publisher &p)
  {
    for (int i = 0; i < MAX_PUBLISHERS; i++)
    {
      if (publishers[i] == 0)
      {
        publishers[i] = &p;
        p.id_ = i + 100 + MAX_SUBSCRIBERS;
        p.nh_ = this;
        return true;
      }
    }
    return false;
  }

  template <typename SubscriberT>
  bool subscribe(SubscriberT &s)
  {
    for (int i = 0; i < MAX_SUBSCRIBERS; i++)
    {
      if (subscribers[i] == 0)
      {
        subscribers[i] = static_cast<Subscriber_ *>(&s);
        s.id_ = i + 100;
        return true;
      }
    }
    return false;
  }

  template <typename MReq, typename MRes, typename ObjT>
  bool advertiseService(ServiceServer<MReq, MRes, ObjT> &srv)
  {
    return advertise(srv.pub) && subscribe(srv);
  }

  template <typename MReq, typename MRes>
  bool serviceClient(ServiceClient<MReq, MRes> &srv)
  {
    return advertise(srv.pub) && subscribe(srv);
  }

  void negotiateTopics()
  {
    rosserial_msgs::TopicInfo ti;
    for (int i = 0; i < MAX_PUBLISHERS; i++)
    {
      if (publishers[i] != 0)
      {
        ti.topic_id = publishers[i]->id_;
        ti.topic_name = publishers[i]->topic_;
        ti.message_type = publishers[i]->msg_->getType();
        ti.md5sum = publishers[i]->msg_->getMD5();
        ti.buffer_size = OUTPUT_SIZE;
        publish(publishers[i]->getEndpointType(), &ti);
      }
    }
    for (int i = 0; i < MAX_SUBSCRIBERS; i++)
    {
      if (subscribers[i] != 0)
      {
        ti.topic_id = subscribers[i]->id_;
        ti.topic_name = subscribers[i]->topic_;
        ti.message_type = subscribers[i]->getMsgType();
        ti.md5sum = subscribers[i]->getMsgMD5();
        ti.buffer_size = INPUT_SIZE;
        publish(subscribers[i]->getEndpointType(), &ti);
      }
    }
    configured_ = true;
  }

  // -- output --------------------------------------------------------------------------------

  virtual int publish(int id, const Msg *msg) override
  {
    if (id >= 100 && !configured_)
      return 0;
    int l = msg->serializedLength();
    if (l > OUTPUT_SIZE - 8)
      return dropped(id);
    l = msg->serialize(message_out + 7);
    if (l > OUTPUT_SIZE - 8)  // a hand-written message without serializedLength()
      return dropped(id);
    return writeFrame(id, l);
  }

private:
  int dropped(int id)
  {
    // (a log message too large for the buffer is dropped silently: no recursion)
    if (id != rosserial_msgs::TopicInfo::ID_LOG)
      logerror("Message from device dropped: message larger than buffer.");
    return -1;
  }

private:
  // Frame the l payload bytes already in message_out + 7 and send them.
  int writeFrame(int id, int l)
  {
    message_out[0] = 0xff;
    message_out[1] = PROTOCOL_VER;
    message_out[2] = (uint8_t)((uint16_t)l & 255);
    message_out[3] = (uint8_t)((uint16_t)l >> 8);
    message_out[4] = 255 - ((message_out[2] + message_out[3]) % 256);
    message_out[5] = (uint8_t)((int16_t)id & 255);
    message_out[6] = (uint8_t)((int16_t)id >> 8);
    int chk = 0;
    for (int i = 5; i < l + 7; i++)
      chk += message_out[i];
    l += 7;
    message_out[l++] = 255 - (chk % 256);
    hardware_.write(message_out, l);
    return l;
  }

public:
  // -- logging -------------------------------------------------------------------------------

  void log(char byte, const char *msg)
  {
    rosserial_msgs::Log l;
    l.level = byte;
    l.msg = msg;
    publish(rosserial_msgs::TopicInfo::ID_LOG, &l);
  }

  void logdebug(const char *msg) { log(rosserial_msgs::Log::ROSDEBUG, msg); }
  void loginfo(const char *msg) { log(rosserial_msgs::Log::INFO, msg); }
  void logwarn(const char *msg) { log(rosserial_msgs::Log::WARN, msg); }
  void logerror(const char *msg) { log(rosserial_msgs::Log::ERROR, msg); }
  void logfatal(const char *msg) { log(rosserial_msgs::Log::FATAL, msg); }

  // -- parameters ----------------------------------------------------------------------------

private:
  bool requestParam(const char *name, int time_out = 1000)
  {
    param_received = false;
    rosserial_msgs::RequestParamRequest req;
    req.name = name;
    publish(rosserial_msgs::TopicInfo::ID_PARAMETER_REQUEST, &req);
    const uint32_t end_time = hardware_.time() + time_out;
    while (!param_received)
    {
      spinOnce();
      if (hardware_.time() > end_time)
      {
        logwarn("Failed to get param: timeout expired");
        return false;
      }
    }
    return true;
  }

  // the values of the last response into the caller's array, when it holds as many as asked for
  template <typename T, typename V>
  bool copyParam(T *param, int length, const V *values, uint32_t count)
  {
    if (length != (int)count)
    {
      logwarn("Failed to get param: length mismatch");
      return false;
    }
    for (int i = 0; i < length; i++)
      param[i] = values[i];
    return true;
  }

public:
  bool getParam(const char *name, int *param, int length = 1, int timeout = 1000)
  {
    return requestParam(name, timeout) && copyParam(param, length, req_param_resp.ints, req_param_resp.ints_length);
  }

  bool getParam(const char *name, float *param, int length = 1, int timeout = 1000)
  {
    return requestParam(name, timeout) && copyParam(param, length, req_param_resp.floats, req_param_resp.floats_length);
  }

  bool getParam(const char *name, char **param, int length = 1, int timeout = 1000)
  {
    if (requestParam(name, timeout))
    {
      if (length == (int)req_param_resp.strings_length)
      {
        // as the original: copied into the caller's buffers (param[i] must point to room for
        // the string and its NUL)
        for (int i = 0; i < length; i++)
          strcpy(param[i], req_param_resp.strings[i]);
        return true;
      }
      logwarn("Failed to get param: length mismatch");
    }
    return false;
  }

  bool getParam(const char *name, bool *param, int length = 1, int timeout = 1000)
  {
    return requestParam(name, timeout) && copyParam(param, length, req_param_resp.ints, req_param_resp.ints_length);
  }
};

}  // namespace ros

#endif
