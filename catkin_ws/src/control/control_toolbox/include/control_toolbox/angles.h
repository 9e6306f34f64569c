// The part of ROS' `angles` package (not in Debian 12) the joint controllers need:
// normalisation and shortest angular distances, with the semantics of angles 1.9.
#pragma once

#include <algorithm>
#include <cmath>

namespace control_toolbox
{
namespace angles
{

/// angle mapped to [0, 2*pi)
inline double normalize_angle_positive(double angle)
{
  const double result = std::fmod(angle, 2.0 * M_PI);
  return result < 0.0 ? result + 2.0 * M_PI : result;
}

/// angle mapped to (-pi, pi]
inline double normalize_angle(double angle)
{
  const double result = std::fmod(angle + M_PI, 2.0 * M_PI);
  return result <= 0.0 ? result + M_PI : result - M_PI;
}

/// shortest signed rotation from `from` to `to`, in (-pi, pi]
inline double shortest_angular_distance(double from, double to) { return normalize_angle(to - from); }

/// the same rotation going the other way round (2*pi for 0)
inline double two_pi_complement(double angle)
{
  if (angle > 2.0 * M_PI || angle < -2.0 * M_PI)
    angle = std::fmod(angle, 2.0 * M_PI);
  if (angle < 0.0)
    return 2.0 * M_PI + angle;
  if (angle > 0.0)
    return -2.0 * M_PI + angle;
  return 2.0 * M_PI;
}

/// Smallest and largest rotation from `from` that stays inside [left_limit, right_limit];
/// false if `from` is outside the limits.
inline bool find_min_max_delta(double from, double left_limit, double right_limit, double& result_min_delta,
                               double& result_max_delta)
{
  const double to_left = shortest_angular_distance(from, left_limit);
  const double to_right = shortest_angular_distance(from, right_limit);
  const double to_left_other = two_pi_complement(to_left);
  const double to_right_other = two_pi_complement(to_right);

  if (to_left == 0.0)
  {
    result_min_delta = to_left;
    result_max_delta = std::max(to_right, to_right_other);
    return true;
  }
  if (to_right == 0.0)
  {
    result_max_delta = to_right;
    result_min_delta = std::min(to_left, to_left_other);
    return true;
  }

  double delta_min = to_left, delta_min_other = to_left_other;
  if (to_left_other < delta_min)
    std::swap(delta_min, delta_min_other);
  double delta_max = to_right, delta_max_other = to_right_other;
  if (to_right_other > delta_max)
    std::swap(delta_max, delta_max_other);

  if (delta_min <= delta_max_other || delta_max >= delta_min_other)
  {
    result_min_delta = delta_max_other;
    result_max_delta = delta_min_other;
    return left_limit == -M_PI && right_limit == M_PI;
  }
  result_min_delta = delta_min;
  result_max_delta = delta_max;
  return true;
}

/// Shortest rotation from `from` to `to` that does not cross the limits [left_limit,
/// right_limit] (a revolute joint cannot go the other way round). Returns false when `from`
/// or `to` is outside the limits; `shortest_angle` then holds the rotation that best moves
/// toward the allowed range.
inline bool shortest_angular_distance_with_limits(double from, double to, double left_limit, double right_limit,
                                                  double& shortest_angle)
{
  double min_delta = -2.0 * M_PI, max_delta = 2.0 * M_PI;
  double min_delta_to = -2.0 * M_PI, max_delta_to = 2.0 * M_PI;
  const bool from_inside = find_min_max_delta(from, left_limit, right_limit, min_delta, max_delta);
  const double delta = shortest_angular_distance(from, to);
  const double delta_other = two_pi_complement(delta);
  const double closer = std::fabs(delta) < std::fabs(delta_other) ? delta : delta_other;

  if (from_inside)
  {
    if (delta >= min_delta && delta <= max_delta)
    {
      shortest_angle = delta;
      return true;
    }
    if (delta_other >= min_delta && delta_other <= max_delta)
    {
      shortest_angle = delta_other;
      return true;
    }
    // `to` is outside the limits: head for the nearer limit
    find_min_max_delta(to, left_limit, right_limit, min_delta_to, max_delta_to);
    if (std::fabs(min_delta_to) < std::fabs(max_delta_to))
      shortest_angle = std::max(delta, delta_other);
    else if (std::fabs(min_delta_to) > std::fabs(max_delta_to))
      shortest_angle = std::min(delta, delta_other);
    else
      shortest_angle = closer;
    return false;
  }

  // `from` is outside the limits
  find_min_max_delta(to, left_limit, right_limit, min_delta_to, max_delta_to);
  if (std::fabs(min_delta) < std::fabs(max_delta))
    shortest_angle = std::min(delta, delta_other);
  else if (std::fabs(min_delta) > std::fabs(max_delta))
    shortest_angle = std::max(delta, delta_other);
  else
    shortest_angle = closer;
  return false;
}

/// Shortest rotation from `from` to `to` for limits spanning 2*pi or more (angles are not
/// wrapped there): tries the short way, then the other way round, keeping `from + rotation` in
/// [left_limit, right_limit]. Returns false when neither fits or `from` is outside the limits.
inline bool shortest_angular_distance_with_large_limits(double from, double to, double left_limit,
                                                        double right_limit, double& shortest_angle)
{
  double delta = shortest_angular_distance(from, to);
  double delta_other = two_pi_complement(delta);
  if (std::fabs(delta) > std::fabs(delta_other))
    std::swap(delta, delta_other);

  if (left_limit > right_limit)
  {
    shortest_angle = delta;
    return false;
  }
  const bool from_inside = left_limit <= from && from <= right_limit;
  for (double candidate : {delta, delta_other})
  {
    const double reached = from + candidate;
    if (left_limit <= reached && reached <= right_limit)
    {
      shortest_angle = candidate;
      return from_inside;
    }
  }
  shortest_angle = delta;
  return false;
}

/// Position error of a revolute joint as the ROS 1 position controllers compute it.
inline double revolute_error(double current, double target, double lower, double upper)
{
  double error = 0.0;
  if (upper - lower >= 2.0 * M_PI)
    shortest_angular_distance_with_large_limits(current, target, lower, upper, error);
  else
    shortest_angular_distance_with_limits(current, target, lower, upper, error);
  return error;
}

}  // namespace angles
}  // namespace control_toolbox
