#include "obstacle_cloud_filter/obstacle_filter.h"
#include "synthetic_cloud.h"

#include <gtest/gtest.h>

using obstacle_cloud_filter::FilterParams;
using obstacle_cloud_filter::FilterStats;
using obstacle_cloud_filter::filterObstacles;

namespace
{
FilterParams sceneParams()
{
  FilterParams p;
  p.filter_field_name = "x";  // the scene's forward axis
  p.filter_limit_min = 0.0;
  p.filter_limit_max = 3.0;
  p.leaf_size = 0.02;
  return p;
}
}  // namespace

TEST(ObstacleFilter, RemovesFloorFarPointsAndNaNsKeepsTheBox)
{
  const auto in = obstacle_cloud_filter::test::scene(160, 120);
  pcl::PointCloud<pcl::PointXYZ> out;
  FilterStats s;
  filterObstacles(in, sceneParams(), out, &s);
  EXPECT_EQ(s.input, in.size());
  EXPECT_LT(s.after_passthrough, s.input);
  EXPECT_LT(s.after_voxel, s.after_passthrough);
  EXPECT_GT(s.plane_inliers, 0u);
  // the removed plane is the floor: normal along z, through the origin
  EXPECT_NEAR(std::abs(s.plane[2]), 1.0, 0.01);
  EXPECT_NEAR(s.plane[3], 0.0, 0.01);
  ASSERT_GT(out.size(), 50u);
  size_t box = 0;
  for (const auto& p : out.points)
  {
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    EXPECT_LE(p.x, 3.0f) << "a far-wall point passed the pass-through";
    const bool in_box = p.x >= 0.98f && p.x <= 1.32f && std::abs(p.y) <= 0.17f && p.z <= 0.32f;
    box += in_box;
    EXPECT_TRUE(in_box || p.z > 0.02f) << "a floor point survived at " << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_GE(box, out.size() * 95 / 100);
}

TEST(ObstacleFilter, StagesCanBeDisabled)
{
  const auto in = obstacle_cloud_filter::test::scene(80, 60);
  FilterParams p = sceneParams();
  p.leaf_size = 0.0;
  p.remove_plane = false;
  pcl::PointCloud<pcl::PointXYZ> out;
  FilterStats s;
  filterObstacles(in, p, out, &s);
  EXPECT_EQ(s.after_voxel, s.after_passthrough);
  EXPECT_EQ(out.size(), s.after_passthrough);
  p.filter_limit_negative = true;  // keep only what is outside [0, 3]: the far wall
  filterObstacles(in, p, out, &s);
  for (const auto& pt : out.points)
    EXPECT_FLOAT_EQ(pt.x, 5.0f);
}

TEST(ObstacleFilter, EmptyAndAllNaNCloudsGiveEmptyOutput)
{
  pcl::PointCloud<pcl::PointXYZ> in, out;
  filterObstacles(in, sceneParams(), out);
  EXPECT_TRUE(out.empty());
  in.push_back(pcl::PointXYZ(NAN, NAN, NAN));
  filterObstacles(in, sceneParams(), out);
  EXPECT_TRUE(out.empty());
}

TEST(ObstacleFilter, ValidateNamesTheBadParameter)
{
  FilterParams p;
  EXPECT_EQ(obstacle_cloud_filter::validate(p), "");
  p.filter_field_name = "w";
  EXPECT_EQ(obstacle_cloud_filter::validate(p).rfind("filter_field_name:", 0), 0u);
  p = FilterParams();
  p.filter_limit_min = 2.0;
  p.filter_limit_max = 1.0;
  EXPECT_EQ(obstacle_cloud_filter::validate(p).rfind("filter_limit_min", 0), 0u);
  p = FilterParams();
  p.leaf_size = -1;
  EXPECT_EQ(obstacle_cloud_filter::validate(p).rfind("leaf_size:", 0), 0u);
  p = FilterParams();
  p.distance_threshold = 0;
  EXPECT_EQ(obstacle_cloud_filter::validate(p).rfind("distance_threshold:", 0), 0u);
}
