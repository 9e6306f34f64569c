// The azimuth bins of the lidar's one-origin casts (raycast.cpp, RayScene::cast).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace ode_sim {

// Items of one ray origin by azimuth: a ray can only enter an item whose world bounds' xy
// rectangle its xy direction points into, so each of kBins bins lists (in the given order)
// the items whose rectangle's azimuth interval, seen from the origin and widened by kMargin,
// overlaps it; a rectangle around the origin is in every bin, a vertical ray sees all items.
class AzimuthBins {
 public:
  template <typename ItemT>
  void build(const std::vector<ItemT>& items, const std::vector<int>& order, const double* o) {
    start_.assign(kBins + 1, 0);
    std::vector<std::pair<int, int>> span(order.size());  // first bin, bins spanned
    for (size_t s = 0; s < order.size(); ++s) {
      const ItemT& it = items[order[s]];
      span[s] = {0, kBins};
      if (o[0] < it.lo[0] || o[0] > it.hi[0] || o[1] < it.lo[1] || o[1] > it.hi[1]) {
        const double cx = 0.5 * (it.lo[0] + it.hi[0]) - o[0];
        const double cy = 0.5 * (it.lo[1] + it.hi[1]) - o[1];
        const double ac = std::atan2(cy, cx);
        double lo = 0.0, hi = 0.0;
        for (int k = 0; k < 4; ++k) {
          const double x = ((k & 1) ? it.hi[0] : it.lo[0]) - o[0];
          const double y = ((k & 2) ? it.hi[1] : it.lo[1]) - o[1];
          double da = std::atan2(y, x) - ac;
          if (da > kPi) da -= 2 * kPi;
          if (da < -kPi) da += 2 * kPi;
          lo = std::min(lo, da);
          hi = std::max(hi, da);
        }
        const int b0 = bin(ac + lo - kMargin);
        const int b1 = bin(ac + hi + kMargin);
        if (b1 - b0 + 1 < kBins) span[s] = {b0, b1 - b0 + 1};
      }
      for (int k = 0; k < span[s].second; ++k) ++start_[wrap(span[s].first + k) + 1];
    }
    for (int b = 0; b < kBins; ++b) start_[b + 1] += start_[b];
    list_.resize(start_[kBins]);
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (size_t s = 0; s < order.size(); ++s)
      for (int k = 0; k < span[s].second; ++k) list_[fill[wrap(span[s].first + k)]++] = order[s];
  }

  // the items a ray of direction d may enter (all of `order` for a vertical ray)
  void lookup(const double* d, const std::vector<int>& order, const int*& items, size_t& n) const {
    if (d[0] == 0.0 && d[1] == 0.0) {
      items = order.data();
      n = order.size();
      return;
    }
    const int b = wrap(bin(std::atan2(d[1], d[0])));
    items = list_.data() + start_[b];
    n = static_cast<size_t>(start_[b + 1] - start_[b]);
  }

 private:
  static constexpr int kBins = 256;
  static constexpr double kPi = 3.14159265358979323846;
  static constexpr double kMargin = 1e-6;  // rad: far more than atan2's rounding
  static int bin(double a) { return static_cast<int>(std::floor((a + kPi) * (kBins / (2 * kPi)))); }
  static int wrap(int b) { return ((b % kBins) + kBins) % kBins; }
  std::vector<int> start_, list_;
};

}  // namespace ode_sim
