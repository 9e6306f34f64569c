// rosserial_server (re-implementation): the session, the rosserial protocol's host side.
#include "rosserial_server/session.h"

#include <condition_variable>
#include <mutex>
#include <thread>

#include <ros/service_callback_helper.h>
#include <ros/serialization.h>
#include <topic_tools/shape_shifter.h>

#include "rosserial_server/msg_lookup.h"
#include "session_codec.h"

namespace ser = ros::serialization;

namespace rosserial_server
{

namespace
{
const double TOPIC_REQUEST_PERIOD = 1.0;  // s between topic requests until the device answers
const double SERVICE_TIMEOUT = 5.0;       // s a ROS caller waits for the device's response
const double REQUIRE_CHECK_DELAY = 1.0;   // s after a topic request: ~require checked

// The message bytes of a SerializedMessage (after any length prefix).
std::vector<uint8_t> body(const ros::SerializedMessage& m)
{
  const uint8_t* start = m.message_start ? m.message_start : m.buf.get();
  const size_t skip = start - m.buf.get();
  return std::vector<uint8_t>(start, start + (m.num_bytes - skip));
}

double since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

struct PublisherEntry
{
  std::string topic, type, md5;
  topic_tools::ShapeShifter shifter;
  ros::Publisher pub;

  void publish(const std::vector<uint8_t>& payload)
  {
    ser::IStream s(const_cast<uint8_t*>(payload.data()), (uint32_t)payload.size());
    shifter.read(s);
    pub.publish(shifter);
  }
};

struct SubscriberEntry
{
  std::string topic, type, md5;
  std::shared_ptr<std::atomic<int>> topic_id = std::make_shared<std::atomic<int>>(0);
  ros::Subscriber sub;
};

// A service served by the device: ROS callers -> device, the device's answer -> caller.
struct DeviceServiceEntry
{
  std::string name, type, request_md5, response_md5;
  std::shared_ptr<FdStream> stream;
  int request_id = -1;   // the device's subscriber: requests go there
  int response_id = -1;  // the device's publisher: responses come from there
  ros::ServiceServer server;
  std::mutex call_mutex;  // one call at a time: the device answers in order
  std::mutex m;
  std::condition_variable cv;
  bool waiting = false, answered = false;
  std::vector<uint8_t> response;

  void onResponse(const std::vector<uint8_t>& payload)
  {
    std::lock_guard<std::mutex> lock(m);
    if (!waiting)
      return;
    response = payload;
    answered = true;
    cv.notify_all();
  }
};

class DeviceServiceHelper : public ros::ServiceCallbackHelper
{
public:
  explicit DeviceServiceHelper(std::shared_ptr<DeviceServiceEntry> entry) : entry_(entry) {}

  bool call(ros::ServiceCallbackHelperCallParams& params) override
  {
    DeviceServiceEntry& e = *entry_;
    std::lock_guard<std::mutex> one(e.call_mutex);
    std::vector<uint8_t> request = body(params.request);
    bool ok = false;
    std::string error;
    {
      std::unique_lock<std::mutex> lock(e.m);
      e.waiting = true;
      e.answered = false;
      if (e.request_id < 0)
        error = "the device has not declared the request side of " + e.name;
      else
      {
        std::vector<uint8_t> frame = encodeFrame((uint16_t)e.request_id, request.data(), request.size());
        lock.unlock();
        const bool sent = e.stream->write(frame.data(), frame.size());
        lock.lock();
        if (!sent)
          error = "the device of " + e.name + " is gone";
        else if (!e.cv.wait_for(lock, std::chrono::duration<double>(SERVICE_TIMEOUT), [&] { return e.answered; }))
          error = "no response from the device within 5 s";
        else
          ok = true;
      }
      e.waiting = false;
    }
    ros::SerializedMessage& out = params.response;
    if (ok)
    {
      const std::vector<uint8_t>& r = e.response;
      out.num_bytes = r.size() + 5;
      out.buf.reset(new uint8_t[out.num_bytes]);
      ser::OStream s(out.buf.get(), (uint32_t)out.num_bytes);
      ser::serialize(s, (uint8_t)1);
      ser::serialize(s, (uint32_t)r.size());
      if (!r.empty())
        memcpy(s.advance((uint32_t)r.size()), r.data(), r.size());
      return true;
    }
    ROS_ERROR("Service %s: %s", e.name.c_str(), error.c_str());
    out.num_bytes = error.size() + 5;
    out.buf.reset(new uint8_t[out.num_bytes]);
    ser::OStream s(out.buf.get(), (uint32_t)out.num_bytes);
    ser::serialize(s, (uint8_t)0);
    ser::serialize(s, error);
    return false;
  }

private:
  std::shared_ptr<DeviceServiceEntry> entry_;
};

// A ROS service the device calls.
struct RosServiceEntry
{
  std::string name, type, md5;
  int request_id = -1;   // the device's publisher: requests come from there
  int response_id = -1;  // the device's subscriber: responses go there
};

Session::Session(const ros::NodeHandle& nh, std::shared_ptr<FdStream> stream) : nh_(nh), stream_(stream) {}

Session::~Session()
{
  stream_->close();
  for (auto& kv : subscribers_)
    kv.second->sub.shutdown();
  for (auto& kv : device_services_)
    kv.second->server.shutdown();
}

void Session::send(uint16_t topic_id, const std::vector<uint8_t>& payload)
{
  std::vector<uint8_t> frame = encodeFrame(topic_id, payload.data(), payload.size());
  stream_->write(frame.data(), frame.size());
}

void Session::requestTopics()
{
  ROS_INFO("Requesting topics...");
  send(rosserial_msgs::TopicInfo::ID_PUBLISHER, std::vector<uint8_t>());
  last_request_ = Clock::now();
  require_check_pending_ = true;
}

void Session::run(const std::function<bool()>& keep_going)
{
  last_rx_ = Clock::now();
  requestTopics();
  std::vector<uint8_t> buf(65536);  // a whole UDP datagram (udp_socket_node) fits
  while (keep_going())
  {
    int n = stream_->read(buf.data(), buf.size(), 100);
    if (n < 0)
    {
      ROS_WARN("rosserial_server: %s closed", stream_->name().c_str());
      break;
    }
    for (int i = 0; i < n; ++i)
    {
      switch (parser_.feed(buf[i]))
      {
        case FrameParser::FRAME:
          last_rx_ = Clock::now();
          try
          {
            handle(parser_.topicId(), parser_.payload());
          }
          catch (const std::exception& e)
          {
            ROS_ERROR("Error handling a message on topic id %d (%zu bytes): %s", parser_.topicId(),
                      parser_.payload().size(), e.what());
          }
          break;
        case FrameParser::BAD_VERSION:
          ROS_ERROR(
              "Mismatched protocol version in packet (0x%02x): lost sync or rosserial_python "
              "is from different ros release than the rosserial client",
              parser_.badVersion());
          break;
        case FrameParser::BAD_LENGTH_CHECKSUM:
          ROS_INFO("Wrong checksum for msg length, dropping message.");
          break;
        case FrameParser::BAD_CHECKSUM:
          ROS_INFO("wrong checksum for topic id and msg");
          break;
        case FrameParser::TOO_LONG:
          ROS_WARN("Frame longer than the buffer, dropping message.");
          break;
        case FrameParser::NONE:
          break;
      }
    }
    if (!synced_ && since(last_request_) > TOPIC_REQUEST_PERIOD)
      requestTopics();
    if (require_check_pending_ && since(last_request_) > REQUIRE_CHECK_DELAY)
      checkRequiredTopics();
    if (synced_ && since(last_rx_) > sync_timeout_)
    {
      ROS_ERROR("Lost sync with device, restarting...");
      synced_ = false;
      requestTopics();
    }
  }
  if (ros::ok())
    return;
  // shutting down: tell the device to stop sending
  send(rosserial_msgs::TopicInfo::ID_TX_STOP, std::vector<uint8_t>());
}

void Session::handle(uint16_t id, const std::vector<uint8_t>& payload)
{
  typedef rosserial_msgs::TopicInfo T;
  if (id >= 100)
  {
    auto it = endpoints_.find(id);
    if (it == endpoints_.end())
    {
      ROS_ERROR_THROTTLE(1.0, "Tried to publish before configured, topic id %d", id);
      if (since(last_request_) > TOPIC_REQUEST_PERIOD)
        requestTopics();
      return;
    }
    it->second(payload);
    return;
  }
  switch (id)
  {
    case T::ID_PUBLISHER:
      if (payload.empty())
        requestTopics();  // our ros_lib announces a (re)start with an empty frame
      else
        setupPublisher(decode<T>(payload));
      break;
    case T::ID_SUBSCRIBER:
      setupSubscriber(decode<T>(payload));
      break;
    case T::ID_SERVICE_SERVER + T::ID_PUBLISHER:
      setupServiceServer(decode<T>(payload), true);
      break;
    case T::ID_SERVICE_SERVER + T::ID_SUBSCRIBER:
      setupServiceServer(decode<T>(payload), false);
      break;
    case T::ID_SERVICE_CLIENT + T::ID_PUBLISHER:
      setupServiceClient(decode<T>(payload), true);
      break;
    case T::ID_SERVICE_CLIENT + T::ID_SUBSCRIBER:
      setupServiceClient(decode<T>(payload), false);
      break;
    case T::ID_PARAMETER_REQUEST:
      handleParameterRequest(payload);
      break;
    case T::ID_LOG:
      handleLog(payload);
      break;
    case T::ID_TIME:
      handleTimeRequest();
      break;
    case T::ID_TX_STOP:
      ROS_INFO("The device stopped transmitting (TX stop): renegotiating");
      synced_ = false;
      requestTopics();
      break;
    default:
      ROS_WARN("Frame on reserved topic id %d ignored", id);
  }
}

void Session::setupPublisher(const rosserial_msgs::TopicInfo& info)
{
  const MsgInfo mi = lookupMessage(info.message_type);
  if (mi.md5sum != info.md5sum)
    throw std::runtime_error("Checksum does not match: " + mi.md5sum + "," + info.md5sum + " (publisher " +
                             info.topic_name + " [" + info.message_type + "])");
  auto& entry = publishers_[info.topic_name];
  if (!entry || entry->type != info.message_type)
  {
    entry = std::make_shared<PublisherEntry>();
    entry->topic = info.topic_name;
    entry->type = info.message_type;
    entry->md5 = info.md5sum;
    entry->shifter.morph(info.md5sum, info.message_type, mi.full_text, "true");
    // latched, as our serial_node.py: a message sent once right after sync is not lost
    entry->pub = entry->shifter.advertise(nh_, info.topic_name, 10, true);
  }
  std::shared_ptr<PublisherEntry> e = entry;
  endpoints_[info.topic_id] = [e](const std::vector<uint8_t>& p) { e->publish(p); };
  ROS_INFO("Setup publisher on %s [%s]", info.topic_name.c_str(), info.message_type.c_str());
  if (out_buffer_ < 0)
  {
    out_buffer_ = info.buffer_size;
    ROS_INFO("Note: publish buffer size is %d bytes", out_buffer_);
  }
}

void Session::setupSubscriber(const rosserial_msgs::TopicInfo& info)
{
  const MsgInfo mi = lookupMessage(info.message_type);
  if (mi.md5sum != info.md5sum)
    throw std::runtime_error("Checksum does not match: " + mi.md5sum + "," + info.md5sum + " (subscriber " +
                             info.topic_name + " [" + info.message_type + "])");
  auto& entry = subscribers_[info.topic_name];
  if (entry && entry->type != info.message_type)
  {
    entry->sub.shutdown();
    entry.reset();
  }
  if (!entry)
  {
    entry = std::make_shared<SubscriberEntry>();
    entry->topic = info.topic_name;
    entry->type = info.message_type;
    entry->md5 = info.md5sum;
    std::shared_ptr<FdStream> stream = stream_;
    std::shared_ptr<std::atomic<int>> id = entry->topic_id;
    const std::string md5 = info.md5sum, topic = info.topic_name;
    const int limit = info.buffer_size;
    entry->sub = nh_.subscribe<topic_tools::ShapeShifter>(
        info.topic_name, 10,
        [stream, id, md5, topic, limit](const topic_tools::ShapeShifter::ConstPtr& m)
        {
          if (m->getMD5Sum() != md5 && m->getMD5Sum() != "*")
          {
            ROS_ERROR_THROTTLE(5.0, "Message on %s has md5 %s, the device expects %s: dropped", topic.c_str(),
                               m->getMD5Sum().c_str(), md5.c_str());
            return;
          }
          std::vector<uint8_t> data(m->size());
          ser::OStream s(data.data(), (uint32_t)data.size());
          m->write(s);
          if (limit > 0 && (int)data.size() > limit)
          {
            ROS_WARN_THROTTLE(5.0, "Message from ROS network dropped: message larger than buffer.");
            return;
          }
          std::vector<uint8_t> frame = encodeFrame((uint16_t)id->load(), data.data(), data.size());
          stream->write(frame.data(), frame.size());
        });
  }
  entry->topic_id->store(info.topic_id);
  ROS_INFO("Setup subscriber on %s [%s]", info.topic_name.c_str(), info.message_type.c_str());
  if (in_buffer_ < 0)
  {
    in_buffer_ = info.buffer_size;
    ROS_INFO("Note: subscribe buffer size is %d bytes", in_buffer_);
  }
}

void Session::setupServiceServer(const rosserial_msgs::TopicInfo& info, bool device_publisher)
{
  const ServiceInfo si = lookupService(info.message_type);
  const std::string& want = device_publisher ? si.response_md5sum : si.request_md5sum;
  if (want != info.md5sum)
    throw std::runtime_error("Checksum does not match: " + want + "," + info.md5sum + " (service " + info.topic_name +
                             " [" + info.message_type + "])");
  auto& entry = device_services_[info.topic_name];
  if (entry && entry->type != info.message_type)
  {
    entry->server.shutdown();
    entry.reset();
  }
  if (!entry)
  {
    entry = std::make_shared<DeviceServiceEntry>();
    entry->name = info.topic_name;
    entry->type = info.message_type;
    entry->stream = stream_;
    ros::AdvertiseServiceOptions ops;
    ops.service = info.topic_name;
    ops.md5sum = si.md5sum;
    ops.datatype = info.message_type;
    ops.req_datatype = info.message_type + "Request";
    ops.res_datatype = info.message_type + "Response";
    ops.helper = boost::make_shared<DeviceServiceHelper>(entry);
    entry->server = nh_.advertiseService(ops);
    ROS_INFO("Setup service server on %s [%s]", info.topic_name.c_str(), info.message_type.c_str());
  }
  std::shared_ptr<DeviceServiceEntry> e = entry;
  {
    std::lock_guard<std::mutex> lock(e->m);
    if (device_publisher)
      e->response_id = info.topic_id;
    else
      e->request_id = info.topic_id;
  }
  if (device_publisher)
    endpoints_[info.topic_id] = [e](const std::vector<uint8_t>& p) { e->onResponse(p); };
}

void Session::setupServiceClient(const rosserial_msgs::TopicInfo& info, bool device_publisher)
{
  const ServiceInfo si = lookupService(info.message_type);
  const std::string& want = device_publisher ? si.request_md5sum : si.response_md5sum;
  if (want != info.md5sum)
    throw std::runtime_error("Checksum does not match: " + want + "," + info.md5sum + " (service client " +
                             info.topic_name + ")");
  auto& entry = ros_services_[info.topic_name];
  if (!entry || entry->type != info.message_type)
  {
    entry = std::make_shared<RosServiceEntry>();
    entry->name = info.topic_name;
    entry->type = info.message_type;
    entry->md5 = si.md5sum;
    ROS_INFO("Setup service client on %s [%s]", info.topic_name.c_str(), info.message_type.c_str());
  }
  std::shared_ptr<RosServiceEntry> e = entry;
  if (!device_publisher)
  {
    e->response_id = info.topic_id;
    return;
  }
  e->request_id = info.topic_id;
  std::shared_ptr<FdStream> stream = stream_;
  ros::NodeHandle nh = nh_;
  endpoints_[info.topic_id] = [e, stream, nh](const std::vector<uint8_t>& p)
  {
    // the call runs beside the read loop: the device keeps being served while ROS answers
    std::thread(
        [e, stream, nh, p]() mutable
        {
          ros::ServiceClientOptions ops(nh.resolveName(e->name), e->md5, false, ros::M_string());
          ros::ServiceClient client = nh.serviceClient(ops);
          if (!client.waitForExistence(ros::Duration(10.0)))
          {
            ROS_ERROR("Service %s called by the device does not exist", e->name.c_str());
            return;
          }
          ros::SerializedMessage req;
          req.num_bytes = p.size() + 4;
          req.buf.reset(new uint8_t[req.num_bytes]);
          ser::OStream s(req.buf.get(), (uint32_t)req.num_bytes);
          ser::serialize(s, (uint32_t)p.size());
          if (!p.empty())
            memcpy(s.advance((uint32_t)p.size()), p.data(), p.size());
          req.message_start = req.buf.get() + 4;
          ros::SerializedMessage res;
          if (!client.call(req, res, e->md5))
          {
            ROS_ERROR("Call of service %s for the device failed", e->name.c_str());
            return;
          }
          if (e->response_id < 0)
            return;
          std::vector<uint8_t> data = body(res);
          std::vector<uint8_t> frame = encodeFrame((uint16_t)e->response_id, data.data(), data.size());
          stream->write(frame.data(), frame.size());
        })
        .detach();
  };
}

}  // namespace rosserial_server
