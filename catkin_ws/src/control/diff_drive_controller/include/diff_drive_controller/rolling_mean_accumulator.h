// Mean of the last N samples (what diff_drive_controller's odometry took from
// boost::accumulators' rolling_mean).
#pragma once

#include <cstddef>
#include <vector>

namespace diff_drive_controller
{

class RollingMeanAccumulator
{
public:
  /// window_size: number of most recent samples averaged (0 is treated as 1).
  explicit RollingMeanAccumulator(std::size_t window_size = 10) : buffer_(window_size > 0 ? window_size : 1, 0.0) {}

  void accumulate(double value)
  {
    if (count_ == buffer_.size())
      sum_ -= buffer_[next_];
    else
      ++count_;
    buffer_[next_] = value;
    sum_ += value;
    next_ = (next_ + 1) % buffer_.size();
  }

  /// Mean of the samples in the window; 0 before the first sample.
  double getRollingMean() const { return count_ > 0 ? sum_ / static_cast<double>(count_) : 0.0; }

  std::size_t size() const { return count_; }

private:
  std::vector<double> buffer_;
  std::size_t next_ = 0;
  std::size_t count_ = 0;
  double sum_ = 0.0;
};

}  // namespace diff_drive_controller
