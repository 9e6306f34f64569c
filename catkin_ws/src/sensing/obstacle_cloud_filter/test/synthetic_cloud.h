// A synthetic depth-camera-like scene for the tests and the benchmark: a floor (z = 0), a box
// obstacle and a far wall, sampled on a width x height grid, with a few NaN pixels.
#ifndef OBSTACLE_CLOUD_FILTER_SYNTHETIC_CLOUD_H
#define OBSTACLE_CLOUD_FILTER_SYNTHETIC_CLOUD_H

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <limits>

namespace obstacle_cloud_filter
{
namespace test
{

/// Box: x in [1.0, 1.3], y in [-0.15, 0.15], z in [0, 0.3]. Floor: z = 0, x in [0.3, 3]. Far
/// wall: x = 5. Rows alternate between floor, box and wall samples so each is dense.
inline pcl::PointCloud<pcl::PointXYZ> scene(int width, int height, float noise = 0.002f)
{
  pcl::PointCloud<pcl::PointXYZ> c;
  c.width = width;
  c.height = height;
  c.is_dense = false;
  c.points.resize(static_cast<size_t>(width) * height);
  unsigned seed = 12345;
  auto rnd = [&seed]()
  {
    seed = seed * 1103515245u + 12345u;
    return static_cast<float>((seed >> 8) & 0xFFFF) / 65535.0f - 0.5f;
  };
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u)
    {
      pcl::PointXYZ& p = c.points[static_cast<size_t>(v) * width + u];
      const float s = static_cast<float>(u) / (width - 1), t = static_cast<float>(v) / (height - 1);
      const int kind = (u + v) % 7;
      if ((u * 31 + v * 17) % 101 == 0)
      {
        p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
      }
      else if (kind < 4)
      {  // floor
        p.x = 0.3f + 2.7f * t;
        p.y = -1.0f + 2.0f * s;
        p.z = noise * rnd();
      }
      else if (kind < 6)
      {  // box: front face x = 1.0 and top z = 0.3
        if (kind == 4)
        {
          p.x = 1.0f;
          p.y = -0.15f + 0.3f * s;
          p.z = 0.3f * t;
        }
        else
        {
          p.x = 1.0f + 0.3f * t;
          p.y = -0.15f + 0.3f * s;
          p.z = 0.3f;
        }
      }
      else
      {  // far wall, beyond the pass-through limit
        p.x = 5.0f;
        p.y = -2.0f + 4.0f * s;
        p.z = 2.0f * t;
      }
    }
  return c;
}

}  // namespace test
}  // namespace obstacle_cloud_filter

#endif
