// Re-implementation of realtime_tools/realtime_box.h: a value shared between threads under a
// mutex (short critical sections only).
#pragma once

#include <mutex>

namespace realtime_tools
{

template <class T>
class RealtimeBox
{
public:
  explicit RealtimeBox(const T& initial = T()) : thing_(initial) {}

  void set(const T& value)
  {
    std::lock_guard<std::mutex> guard(thing_lock_RT_);
    thing_ = value;
  }

  void get(T& ref)
  {
    std::lock_guard<std::mutex> guard(thing_lock_RT_);
    ref = thing_;
  }

private:
  T thing_;
  std::mutex thing_lock_RT_;
};

}  // namespace realtime_tools
