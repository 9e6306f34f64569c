// MapGrid::computeTargetDistance's hot loop: a 4-connected breadth-first wavefront over a
// grid, from seed cells, around blocked cells. Called from Python through ctypes
// (base_local_planner/map_grid_native.py); plain C ABI, no ROS.
#include <cstddef>
#include <cstdint>
#include <vector>

extern "C" {

// blocked: nx*ny bytes (non-zero = obstacle); seeds: cell indices; out: nx*ny distances.
// Unreached cells get unreachable, blocked cells obstacle_value; a seed is 0 even when it is
// blocked (plan cells are targets whatever their cost, as MapGrid::setTargetCells).
void blp_wavefront(const uint8_t* blocked, int nx, int ny, const int32_t* seeds, int nseeds,
                   int64_t obstacle_value, int64_t unreachable, int64_t* out) {
  const int n = nx * ny;
  std::vector<int32_t> queue;
  queue.reserve(n);
  for (int i = 0; i < n; ++i) {
    out[i] = blocked[i] ? obstacle_value : unreachable;
  }
  for (int k = 0; k < nseeds; ++k) {
    const int32_t s = seeds[k];
    if (s < 0 || s >= n || out[s] == 0) {
      continue;
    }
    out[s] = 0;
    queue.push_back(s);
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int32_t i = queue[head];
    const int64_t d = out[i] + 1;
    const int x = i % nx;
    const int32_t nb[4] = {x > 0 ? i - 1 : -1, x < nx - 1 ? i + 1 : -1, i >= nx ? i - nx : -1,
                           i < n - nx ? i + nx : -1};
    for (int32_t j : nb) {
      if (j >= 0 && out[j] == unreachable) {
        out[j] = d;
        queue.push_back(j);
      }
    }
  }
}

}  // extern "C"
