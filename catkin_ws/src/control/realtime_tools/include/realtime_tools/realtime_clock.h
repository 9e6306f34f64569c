// Re-implementation of realtime_tools/realtime_clock.h: estimate ros::Time::now() from the
// realtime loop's own time without calling the (possibly blocking) ROS clock there.
#pragma once

#include <mutex>
#include <thread>

#include <ros/time.h>

namespace realtime_tools
{

class RealtimeClock
{
public:
  RealtimeClock();
  ~RealtimeClock();
  RealtimeClock(const RealtimeClock&) = delete;
  RealtimeClock& operator=(const RealtimeClock&) = delete;

  /// ROS time corresponding to the loop's time `realtime_time` (offset learned by a
  /// non-realtime thread; the first call returns `realtime_time` itself).
  ros::Time now(const ros::Time& realtime_time);

private:
  void loop();

  std::mutex mutex_;
  bool running_ = true;
  bool have_offset_ = false;
  bool request_ = false;
  ros::Time last_realtime_time_;
  ros::Duration offset_;
  std::thread thread_;
};

}  // namespace realtime_tools
