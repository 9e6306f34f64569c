#ifndef OBSTACLE_CLOUD_FILTER_OBSTACLE_FILTER_H
#define OBSTACLE_CLOUD_FILTER_OBSTACLE_FILTER_H

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>

namespace obstacle_cloud_filter
{

/// Parameters of the filter chain, with the node's defaults. Lengths in [m].
struct FilterParams
{
  std::string filter_field_name = "z";  ///< PassThrough field ("" disables the stage)
  double filter_limit_min = 0.0;        ///< PassThrough lower bound [m]
  double filter_limit_max = 3.0;        ///< PassThrough upper bound [m]
  bool filter_limit_negative = false;   ///< keep the points outside the limits instead
  double leaf_size = 0.02;              ///< VoxelGrid leaf [m] (0 disables the stage)
  bool remove_plane = true;             ///< RANSAC: remove the dominant plane (floor)
  double distance_threshold = 0.02;     ///< RANSAC inlier distance [m]
  int max_iterations = 100;             ///< RANSAC iterations
  int min_plane_inliers = 200;          ///< smaller planes are kept (not a floor)
};

/// What one run removed, for logging and tests.
struct FilterStats
{
  size_t input = 0, after_passthrough = 0, after_voxel = 0, plane_inliers = 0, output = 0;
  double plane[4] = { 0, 0, 0, 0 };  ///< ax + by + cz + d = 0 of the removed plane
};

/// Returns an empty string when the parameters are valid, else "<param>: what is wrong".
std::string validate(const FilterParams& p);

/// PassThrough -> VoxelGrid -> RANSAC plane removal; NaN points are always dropped.
/// No ROS: the node converts PointCloud2 <-> pcl::PointCloud around it.
void filterObstacles(const pcl::PointCloud<pcl::PointXYZ>& in, const FilterParams& p,
                     pcl::PointCloud<pcl::PointXYZ>& out, FilterStats* stats = nullptr);

}  // namespace obstacle_cloud_filter

#endif
