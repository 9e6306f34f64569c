// Re-implementation of realtime_tools/realtime_publisher.h (ROS 1 realtime_tools 1.16 API).
// The realtime loop fills msg_ under trylock() and hands it to a publishing thread with
// unlockAndPublish(); the loop itself never calls ros::Publisher::publish.
// Unlike the original, which refuses trylock() until the publishing thread has taken the one
// message handed over, up to queue_size handed-over messages may wait for that thread: a
// simulation running many times faster than real time calls the loop faster than a busy
// machine wakes the thread, and the original then drops messages (diff_drive_controller's odom
// lost 0.3-1 % at 20x real time on 2 cores). trylock() refuses once queue_size wait.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <ros/node_handle.h>
#include <ros/publisher.h>

namespace realtime_tools
{

template <class Msg>
class RealtimePublisher
{
public:
  /// The message to fill between trylock()/lock() and unlockAndPublish()/unlock().
  Msg msg_;

  RealtimePublisher(const ros::NodeHandle& node, const std::string& topic, int queue_size, bool latched = false)
  {
    init(node, topic, queue_size, latched);
  }

  RealtimePublisher() = default;
  RealtimePublisher(const RealtimePublisher&) = delete;
  RealtimePublisher& operator=(const RealtimePublisher&) = delete;

  ~RealtimePublisher()
  {
    stop();
    if (thread_.joinable())
      thread_.join();
    publisher_.shutdown();
  }

  void init(const ros::NodeHandle& node, const std::string& topic, int queue_size, bool latched = false)
  {
    topic_ = topic;
    node_ = node;
    publisher_ = node_.advertise<Msg>(topic, queue_size, latched);
    max_pending_ = queue_size > 0 ? static_cast<std::size_t>(queue_size) : 1u;
    keep_running_ = true;
    turn_ = REALTIME;  // trylock() succeeds from now on, before the thread has even started
    thread_ = std::thread(&RealtimePublisher::publishingLoop, this);
  }

  /// Ask the publishing thread to end (the destructor waits for it).
  void stop()
  {
    {
      std::lock_guard<std::mutex> guard(msg_mutex_);
      keep_running_ = false;
    }
    updated_cond_.notify_one();
  }

  bool is_running() const { return is_running_; }

  /// Non-blocking: true when msg_ may be written (fewer than queue_size handed-over messages
  /// wait for the publishing thread).
  bool trylock()
  {
    if (msg_mutex_.try_lock())
    {
      if (turn_ == REALTIME)
        return true;
      msg_mutex_.unlock();
    }
    return false;
  }

  /// Publish msg_ from the publishing thread; call after a successful trylock()/lock().
  void unlockAndPublish()
  {
    pending_.push_back(msg_);
    if (pending_.size() >= max_pending_)
      turn_ = NON_REALTIME;
    msg_mutex_.unlock();
    updated_cond_.notify_one();
  }

  /// Blocking lock of msg_ (not for the realtime loop).
  void lock() { msg_mutex_.lock(); }

  void unlock() { msg_mutex_.unlock(); }

private:
  void publishingLoop()
  {
    is_running_ = true;
    while (true)
    {
      Msg outgoing;
      {
        std::unique_lock<std::mutex> guard(msg_mutex_);
        updated_cond_.wait(guard, [this] { return !pending_.empty() || !keep_running_; });
        if (!keep_running_)
          break;
        outgoing = std::move(pending_.front());
        pending_.pop_front();
        turn_ = REALTIME;
      }
      publisher_.publish(outgoing);
    }
    is_running_ = false;
  }

  enum
  {
    REALTIME,
    NON_REALTIME,
    LOOP_NOT_STARTED
  };

  std::string topic_;
  ros::NodeHandle node_;
  ros::Publisher publisher_;
  std::atomic<bool> is_running_{ false };
  bool keep_running_{ false };
  std::thread thread_;
  std::mutex msg_mutex_;
  std::condition_variable updated_cond_;
  std::deque<Msg> pending_;  // handed over, not yet published (under msg_mutex_)
  std::size_t max_pending_{ 1 };
  std::atomic<int> turn_{ LOOP_NOT_STARTED };
};

template <class Msg>
using RealtimePublisherSharedPtr = std::shared_ptr<RealtimePublisher<Msg>>;

}  // namespace realtime_tools
