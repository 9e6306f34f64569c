#include <realtime_tools/realtime_clock.h>

#include <chrono>

namespace realtime_tools
{

RealtimeClock::RealtimeClock() : thread_(&RealtimeClock::loop, this) {}

RealtimeClock::~RealtimeClock()
{
  {
    std::lock_guard<std::mutex> guard(mutex_);
    running_ = false;
  }
  thread_.join();
}

ros::Time RealtimeClock::now(const ros::Time& realtime_time)
{
  std::unique_lock<std::mutex> guard(mutex_, std::try_to_lock);
  if (!guard.owns_lock())
    return realtime_time;  // the estimator is busy: answer without waiting
  last_realtime_time_ = realtime_time;
  request_ = true;
  return have_offset_ ? realtime_time + offset_ : realtime_time;
}

void RealtimeClock::loop()
{
  while (true)
  {
    {
      std::lock_guard<std::mutex> guard(mutex_);
      if (!running_)
        return;
      if (request_ && ros::Time::isValid())
      {
        offset_ = ros::Time::now() - last_realtime_time_;
        have_offset_ = true;
        request_ = false;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

}  // namespace realtime_tools
