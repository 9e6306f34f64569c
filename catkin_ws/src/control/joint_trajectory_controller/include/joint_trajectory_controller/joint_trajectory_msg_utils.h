// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
// Checks and look-ups on trajectory_msgs/JointTrajectory.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <ros/console.h>
#include <ros/time.h>
#include <trajectory_msgs/JointTrajectory.h>

namespace joint_trajectory_controller
{
namespace internal
{
/// Comparator of findPoint: true if \p time comes before \p point of a message starting at msg_start_time.
class IsBeforePoint
{
public:
  IsBeforePoint(const ros::Time& msg_start_time) : msg_start_time_(msg_start_time) {}

  bool operator()(const ros::Time& time, const trajectory_msgs::JointTrajectoryPoint& point) const
  {
    return time < msg_start_time_ + point.time_from_start;
  }

private:
  ros::Time msg_start_time_;
};

/// The message's start time: header.stamp, or \p time when the stamp is zero.
inline ros::Time startTime(const trajectory_msgs::JointTrajectory& msg, const ros::Time& time)
{
  return msg.header.stamp.isZero() ? time : msg.header.stamp;
}
}  // namespace internal

/// True if every non-empty field of \p point has \p joint_dim values (an empty field is "not given").
inline bool isValid(const trajectory_msgs::JointTrajectoryPoint& point, const unsigned int joint_dim)
{
  auto ok = [joint_dim](const std::vector<double>& v) { return v.empty() || v.size() == joint_dim; };
  return ok(point.positions) && ok(point.velocities) && ok(point.accelerations);
}

/// True if every point's fields agree in size with the joint names (logs the first bad point).
inline bool isValid(const trajectory_msgs::JointTrajectory& msg)
{
  for (std::size_t i = 0; i < msg.points.size(); ++i)
  {
    if (!isValid(msg.points[i], msg.joint_names.size()))
    {
      ROS_ERROR_STREAM("Invalid trajectory point at index: "
                       << i << ". Size mismatch in joint names, position, velocity or acceleration data.");
      return false;
    }
  }
  return true;
}

/// True if each point's time_from_start is later than its predecessor's.
inline bool isTimeStrictlyIncreasing(const trajectory_msgs::JointTrajectory& msg)
{
  for (std::size_t i = 1; i < msg.points.size(); ++i)
    if (!(msg.points[i - 1].time_from_start < msg.points[i].time_from_start))
      return false;
  return true;
}

/**
 * \brief The last point of \p msg reached at or before \p time (the message starting at its
 * stamp, or at \p time if the stamp is zero); points.end() if every point comes later.
 */
inline std::vector<trajectory_msgs::JointTrajectoryPoint>::const_iterator findPoint(
    const trajectory_msgs::JointTrajectory& msg, const ros::Time& time)
{
  const internal::IsBeforePoint before(internal::startTime(msg, time));
  const auto first = msg.points.begin(), last = msg.points.end();
  if (first == last || before(time, *first))
    return last;
  auto after = std::upper_bound(first, last, time, before);
  return --after;
}

}  // namespace joint_trajectory_controller
