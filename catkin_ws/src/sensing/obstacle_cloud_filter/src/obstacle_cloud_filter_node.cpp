// obstacle_cloud_filter_node: points (sensor_msgs/PointCloud2) -> obstacles (the cloud without
// far/near points and the floor plane, voxel-downsampled). Wiring only; see obstacle_filter.cpp.
#include "obstacle_cloud_filter/obstacle_filter.h"

#include <pcl/conversions.h>
#include <pcl_conversions/pcl_conversions.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

namespace obstacle_cloud_filter
{

class ObstacleCloudFilterNode
{
public:
  ObstacleCloudFilterNode(ros::NodeHandle& nh, ros::NodeHandle& pnh, const FilterParams& params) : params_(params)
  {
    pub_ = nh.advertise<sensor_msgs::PointCloud2>("obstacles", 1);
    sub_ = nh.subscribe("points", 1, &ObstacleCloudFilterNode::pointsCallback, this);
    (void)pnh;
  }

private:
  void pointsCallback(const sensor_msgs::PointCloud2ConstPtr& msg)
  {
    bool has_xyz[3] = { false, false, false };
    for (const auto& f : msg->fields)
      for (int i = 0; i < 3; ++i)
        if (f.name == std::string(1, static_cast<char>('x' + i)))
          has_xyz[i] = true;
    if (!has_xyz[0] || !has_xyz[1] || !has_xyz[2])
    {
      ROS_WARN_THROTTLE(5.0, "obstacle_cloud_filter: the cloud on %s has no x/y/z fields; ignored",
                        sub_.getTopic().c_str());
      return;
    }
    pcl::PointCloud<pcl::PointXYZ> in, out;
    pcl::fromROSMsg(*msg, in);
    FilterStats stats;
    filterObstacles(in, params_, out, &stats);
    ROS_DEBUG("obstacle_cloud_filter: %zu points -> passthrough %zu -> voxel %zu -> plane %zu -> %zu", stats.input,
              stats.after_passthrough, stats.after_voxel, stats.plane_inliers, stats.output);
    sensor_msgs::PointCloud2 cloud;
    pcl::toROSMsg(out, cloud);
    cloud.header = msg->header;
    pub_.publish(cloud);
  }

  FilterParams params_;
  ros::Publisher pub_;
  ros::Subscriber sub_;
};

}  // namespace obstacle_cloud_filter

int main(int argc, char** argv)
{
  ros::init(argc, argv, "obstacle_cloud_filter");
  ros::NodeHandle nh, pnh("~");
  obstacle_cloud_filter::FilterParams p;
  pnh.param("filter_field_name", p.filter_field_name, p.filter_field_name);
  pnh.param("filter_limit_min", p.filter_limit_min, p.filter_limit_min);
  pnh.param("filter_limit_max", p.filter_limit_max, p.filter_limit_max);
  pnh.param("filter_limit_negative", p.filter_limit_negative, p.filter_limit_negative);
  pnh.param("leaf_size", p.leaf_size, p.leaf_size);
  pnh.param("remove_plane", p.remove_plane, p.remove_plane);
  pnh.param("distance_threshold", p.distance_threshold, p.distance_threshold);
  pnh.param("max_iterations", p.max_iterations, p.max_iterations);
  pnh.param("min_plane_inliers", p.min_plane_inliers, p.min_plane_inliers);
  const std::string error = obstacle_cloud_filter::validate(p);
  if (!error.empty())
  {
    ROS_ERROR("obstacle_cloud_filter: bad parameter %s", error.c_str());
    return 1;
  }
  ROS_INFO(
      "obstacle_cloud_filter: %s in [%g, %g]%s, leaf_size %g m, plane removal %s "
      "(distance_threshold %g m, max_iterations %d, min_plane_inliers %d)",
      p.filter_field_name.c_str(), p.filter_limit_min, p.filter_limit_max, p.filter_limit_negative ? " (negative)" : "",
      p.leaf_size, p.remove_plane ? "on" : "off", p.distance_threshold, p.max_iterations, p.min_plane_inliers);
  obstacle_cloud_filter::ObstacleCloudFilterNode node(nh, pnh, p);
  ros::spin();
  return 0;
}
