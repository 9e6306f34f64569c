// rosserial_server (re-implementation): one rosserial device session over a byte stream: topic
// negotiation (publishers, subscribers, service servers and clients on the device), time sync,
// parameters, device logging, TX stop; resync after garbage; renegotiation after lost sync.
#ifndef ROSSERIAL_SERVER_SESSION_H
#define ROSSERIAL_SERVER_SESSION_H

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <rosserial_msgs/TopicInfo.h>

#include "rosserial_server/frame.h"
#include "rosserial_server/stream.h"

namespace rosserial_server
{

struct PublisherEntry;
struct SubscriberEntry;
struct DeviceServiceEntry;
struct RosServiceEntry;

class Session
{
public:
  // nh: the namespace topics and services are created in (the node's parent namespace)
  Session(const ros::NodeHandle& nh, std::shared_ptr<FdStream> stream);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Bridge until the stream closes or keep_going() turns false.
  void run(const std::function<bool()>& keep_going);

  // seconds without any frame (once synced) before "Lost sync with device, restarting..."
  void setSyncTimeout(double s) { sync_timeout_ = s; }

private:
  typedef std::chrono::steady_clock Clock;

  void handle(uint16_t topic_id, const std::vector<uint8_t>& payload);
  void requestTopics();
  // ~require/publishers and ~require/subscribers (topic name lists) checked 1 s after each
  // topic request: a device missing one is asked for its topics again (the original's rule)
  void checkRequiredTopics();
  void send(uint16_t topic_id, const std::vector<uint8_t>& payload);

  void setupPublisher(const rosserial_msgs::TopicInfo& info);
  void setupSubscriber(const rosserial_msgs::TopicInfo& info);
  void setupServiceServer(const rosserial_msgs::TopicInfo& info, bool device_publisher);
  void setupServiceClient(const rosserial_msgs::TopicInfo& info, bool device_publisher);
  void handleTimeRequest();
  void handleParameterRequest(const std::vector<uint8_t>& payload);
  void handleLog(const std::vector<uint8_t>& payload);

  ros::NodeHandle nh_;
  std::shared_ptr<FdStream> stream_;
  FrameParser parser_;
  double sync_timeout_ = 15.0;
  bool synced_ = false;
  bool require_check_pending_ = false;
  Clock::time_point last_rx_, last_request_;
  int out_buffer_ = -1, in_buffer_ = -1;

  std::map<std::string, std::shared_ptr<PublisherEntry>> publishers_;    // by topic
  std::map<std::string, std::shared_ptr<SubscriberEntry>> subscribers_;  // by topic
  std::map<std::string, std::shared_ptr<DeviceServiceEntry>> device_services_;
  std::map<std::string, std::shared_ptr<RosServiceEntry>> ros_services_;
  // topic id -> what handles a frame from the device on it
  std::map<uint16_t, std::function<void(const std::vector<uint8_t>&)>> endpoints_;
};

}  // namespace rosserial_server

#endif
