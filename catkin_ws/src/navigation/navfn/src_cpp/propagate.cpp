// navfn's potential propagation (NavFn::updateCell in Dijkstra order, optionally A*), the
// hot loop of navfn/navfn.py's propagate(); called through ctypes, plain C ABI, no ROS.
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

namespace {
const double kCostObs = 254.0;
const double kPotHigh = 1.0e10;
}  // namespace

extern "C" {

// costs: nx*ny navfn costs; pot: nx*ny output. Stops `extra` cells after `stop` (-1: never).
void navfn_propagate(const double* costs, int nx, int ny, int goal, int stop, int extra,
                     double h_scale, int sx, int sy, double* pot) {
  const int n = nx * ny;
  for (int i = 0; i < n; ++i) {
    pot[i] = kPotHigh;
  }
  if (goal < 0 || goal >= n || costs[goal] >= kCostObs) {
    return;
  }
  std::vector<uint8_t> done(n, 0);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  pot[goal] = 0.0;
  heap.push({0.0, goal});
  long remaining = -1;
  while (!heap.empty()) {
    const int c = heap.top().second;
    heap.pop();
    if (done[c]) {
      continue;
    }
    done[c] = 1;
    if (remaining >= 0) {
      if (--remaining <= 0) {
        break;
      }
    } else if (c == stop) {
      remaining = extra;
    }
    const int cx = c % nx;
    const int cy = c / nx;
    const int nb[4] = {cx > 0 ? c - 1 : -1, cx < nx - 1 ? c + 1 : -1, cy > 0 ? c - nx : -1,
                       cy < ny - 1 ? c + nx : -1};
    for (int m : nb) {
      if (m < 0 || done[m]) {
        continue;
      }
      const double hf = costs[m];
      if (hf >= kCostObs) {
        continue;
      }
      const int mx = m % nx;
      const int my = m / nx;
      const double l = mx > 0 ? pot[m - 1] : kPotHigh;
      const double r = mx < nx - 1 ? pot[m + 1] : kPotHigh;
      const double u = my > 0 ? pot[m - nx] : kPotHigh;
      const double d = my < ny - 1 ? pot[m + nx] : kPotHigh;
      double ta = l < r ? l : r;
      double tc = u < d ? u : d;
      if (ta > tc) {
        std::swap(ta, tc);
      }
      const double dc = tc - ta;
      double p;
      if (dc >= hf) {
        p = ta + hf;
      } else {
        const double dd = dc / hf;
        p = ta + hf * (-0.2301 * dd * dd + 0.5307 * dd + 0.7040);
      }
      if (p < pot[m]) {
        pot[m] = p;
        double key = p;
        if (h_scale > 0) {
          key += h_scale * std::hypot(double(mx - sx), double(my - sy));
        }
        heap.push({key, m});
      }
    }
  }
}

}  // extern "C"
