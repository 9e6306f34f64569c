// The PCL filter chain: the only translation unit that instantiates PCL's filters.
#include "obstacle_cloud_filter/obstacle_filter.h"

#include <pcl/ModelCoefficients.h>
#include <pcl/filters/extract_indices.h>
#include <pcl/filters/passthrough.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>

namespace obstacle_cloud_filter
{

std::string validate(const FilterParams& p)
{
  if (!p.filter_field_name.empty() && p.filter_field_name != "x" && p.filter_field_name != "y" &&
      p.filter_field_name != "z")
    return "filter_field_name: must be x, y, z or empty, got '" + p.filter_field_name + "'";
  if (!(p.filter_limit_min < p.filter_limit_max))
    return "filter_limit_min/filter_limit_max: min must be below max";
  if (!(p.leaf_size >= 0.0))
    return "leaf_size: must be >= 0 (0 disables the voxel grid)";
  if (!(p.distance_threshold > 0.0))
    return "distance_threshold: must be > 0";
  if (p.max_iterations < 1)
    return "max_iterations: must be >= 1";
  if (p.min_plane_inliers < 3)
    return "min_plane_inliers: must be >= 3";
  return "";
}

void filterObstacles(const pcl::PointCloud<pcl::PointXYZ>& in, const FilterParams& p,
                     pcl::PointCloud<pcl::PointXYZ>& out, FilterStats* stats)
{
  FilterStats s;
  s.input = in.size();
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  // 1. PassThrough (also drops NaN points); without a field only the NaNs go
  cloud->reserve(in.size());
  const int axis = p.filter_field_name == "x"   ? 0
                   : p.filter_field_name == "y" ? 1
                   : p.filter_field_name == "z" ? 2
                                                : -1;
  for (const auto& pt : in.points)
  {
    if (!std::isfinite(pt.x) || !std::isfinite(pt.y) || !std::isfinite(pt.z))
      continue;
    if (axis >= 0)
    {
      const float v = axis == 0 ? pt.x : axis == 1 ? pt.y : pt.z;
      const bool inside = v >= p.filter_limit_min && v <= p.filter_limit_max;
      if (inside == p.filter_limit_negative)
        continue;
    }
    cloud->push_back(pt);
  }
  s.after_passthrough = cloud->size();
  // 2. VoxelGrid
  if (p.leaf_size > 0.0 && !cloud->empty())
  {
    auto voxel = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    pcl::VoxelGrid<pcl::PointXYZ> grid;
    grid.setInputCloud(cloud);
    const float leaf = static_cast<float>(p.leaf_size);
    grid.setLeafSize(leaf, leaf, leaf);
    grid.filter(*voxel);
    cloud = voxel;
  }
  s.after_voxel = cloud->size();
  // 3. RANSAC plane removal
  out.clear();
  if (p.remove_plane && cloud->size() >= static_cast<size_t>(p.min_plane_inliers))
  {
    pcl::SACSegmentation<pcl::PointXYZ> seg;
    seg.setOptimizeCoefficients(true);
    seg.setModelType(pcl::SACMODEL_PLANE);
    seg.setMethodType(pcl::SAC_RANSAC);
    seg.setDistanceThreshold(p.distance_threshold);
    seg.setMaxIterations(p.max_iterations);
    seg.setInputCloud(cloud);
    auto inliers = pcl::make_shared<pcl::PointIndices>();
    pcl::ModelCoefficients coefficients;
    seg.segment(*inliers, coefficients);
    if (inliers->indices.size() >= static_cast<size_t>(p.min_plane_inliers))
    {
      s.plane_inliers = inliers->indices.size();
      for (size_t i = 0; i < 4 && i < coefficients.values.size(); ++i)
        s.plane[i] = coefficients.values[i];
      pcl::ExtractIndices<pcl::PointXYZ> extract;
      extract.setInputCloud(cloud);
      extract.setIndices(inliers);
      extract.setNegative(true);
      extract.filter(out);
    }
    else
    {
      out = *cloud;
    }
  }
  else
  {
    out = *cloud;
  }
  out.header = in.header;
  s.output = out.size();
  if (stats)
    *stats = s;
}

}  // namespace obstacle_cloud_filter
