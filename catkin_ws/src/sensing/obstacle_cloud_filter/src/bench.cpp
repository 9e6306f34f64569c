// Benchmark helper (bench/sensing/run): the filter chain on a 640x480 cloud, printed as the
// median CPU time as a fraction of a 30 Hz camera period. Not part of the test gate.
#include "obstacle_cloud_filter/obstacle_filter.h"
#include "../test/synthetic_cloud.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <vector>

int main()
{
  const auto in = obstacle_cloud_filter::test::scene(640, 480);
  obstacle_cloud_filter::FilterParams p;
  p.filter_field_name = "x";
  p.filter_limit_min = 0.0;
  p.filter_limit_max = 3.0;
  std::vector<double> t, wall;
  pcl::PointCloud<pcl::PointXYZ> out;
  obstacle_cloud_filter::FilterStats s;
  for (int i = 0; i < 15; ++i)
  {
    const auto a = std::chrono::steady_clock::now();
    const std::clock_t c = std::clock();
    obstacle_cloud_filter::filterObstacles(in, p, out, &s);
    t.push_back(static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  std::sort(wall.begin(), wall.end());
  const double median = t[t.size() / 2], period = 1.0 / 30.0;
  std::printf(
      "pcl_filter_640x480: %zu -> %zu points (passthrough %zu, voxel %zu, plane %zu), "
      "median CPU %.2f ms = %.3f of a 30 Hz camera period (wall %.2f ms)\n",
      s.input, s.output, s.after_passthrough, s.after_voxel, s.plane_inliers, median * 1e3, median / period,
      wall[wall.size() / 2] * 1e3);
  return 0;
}
