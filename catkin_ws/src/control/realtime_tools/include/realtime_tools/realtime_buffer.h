// Re-implementation of realtime_tools/realtime_buffer.h (ROS 1 realtime_tools 1.16 API).
// Hands a value from non-realtime threads (subscriber callbacks) to the realtime loop.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <thread>

namespace realtime_tools
{

/// Double buffer: writers (non-realtime) fill one copy under a lock; the realtime reader swaps it
/// in with a try_lock so it never blocks (if the writer holds the lock it reads the old value).
template <class T>
class RealtimeBuffer
{
public:
  RealtimeBuffer() : non_realtime_data_(new T()), realtime_data_(new T()), new_data_available_(false) {}

  explicit RealtimeBuffer(const T& data)
    : non_realtime_data_(new T(data)), realtime_data_(new T(data)), new_data_available_(false)
  {
  }

  RealtimeBuffer(const RealtimeBuffer& source)
    : non_realtime_data_(new T()), realtime_data_(new T()), new_data_available_(false)
  {
    operator=(source);
  }

  RealtimeBuffer& operator=(const RealtimeBuffer& source)
  {
    if (this == &source)
      return *this;
    // copy what the source's realtime side would read now
    T copy = *source.readFromNonRT();
    writeFromNonRT(copy);
    return *this;
  }

  ~RealtimeBuffer() = default;

  /// Realtime side: the newest value written (never blocks).
  T* readFromRT()
  {
    std::unique_lock<std::mutex> guard(mutex_, std::try_to_lock);
    if (guard.owns_lock() && new_data_available_)
    {
      std::swap(realtime_data_, non_realtime_data_);
      new_data_available_ = false;
    }
    return realtime_data_.get();
  }

  /// Non-realtime side: the newest value written (blocks briefly).
  T* readFromNonRT() const
  {
    std::lock_guard<std::mutex> guard(mutex_);
    return new_data_available_ ? non_realtime_data_.get() : realtime_data_.get();
  }

  /// Non-realtime side: publish a new value for the realtime reader.
  void writeFromNonRT(const T& data)
  {
    // the realtime reader only ever try_locks, so spinning here is short
    std::unique_lock<std::mutex> guard(mutex_, std::defer_lock);
    while (!guard.try_lock())
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    *non_realtime_data_ = data;
    new_data_available_ = true;
  }

  /// Set both copies (before the realtime loop runs).
  void initRT(const T& data)
  {
    std::lock_guard<std::mutex> guard(mutex_);
    *non_realtime_data_ = data;
    *realtime_data_ = data;
    new_data_available_ = false;
  }

private:
  std::unique_ptr<T> non_realtime_data_;
  std::unique_ptr<T> realtime_data_;
  bool new_data_available_;
  mutable std::mutex mutex_;
};

}  // namespace realtime_tools
