// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <algorithm>
#include <iterator>

namespace trajectory_interface
{
/**
 * \brief The segment of [first, last) (sorted by start time) that is active at \p time: the last
 * one starting at or before \p time (also past its end, until the next one starts); \p last if
 * \p time precedes them all or the range is empty.
 */
template <class TrajectoryIterator, class Time>
inline TrajectoryIterator findSegment(TrajectoryIterator first, TrajectoryIterator last, const Time& time)
{
  typedef typename std::iterator_traits<TrajectoryIterator>::value_type Segment;
  if (first == last || time < first->startTime())
    return last;
  TrajectoryIterator after =
      std::upper_bound(first, last, time, [](const Time& t, const Segment& s) { return t < s.startTime(); });
  return --after;
}

/// findSegment over a whole sequence container.
template <class Trajectory, class Time>
inline typename Trajectory::const_iterator findSegment(const Trajectory& trajectory, const Time& time)
{
  return findSegment(trajectory.begin(), trajectory.end(), time);
}

/// findSegment returning a non-const iterator (the trajectory is not modified).
template <class Trajectory, class Time>
inline typename Trajectory::iterator findSegment(Trajectory& trajectory, const Time& time)
{
  return findSegment(trajectory.begin(), trajectory.end(), time);
}

/**
 * \brief Sample \p trajectory at \p time into \p state. Returns the active segment (end() if
 * \p time precedes the trajectory, which is then sampled by its first segment; \p state is left
 * as it is for an empty trajectory).
 */
template <class Trajectory>
inline typename Trajectory::const_iterator sample(const Trajectory& trajectory,
                                                  const typename Trajectory::value_type::Time& time,
                                                  typename Trajectory::value_type::State& state)
{
  typename Trajectory::const_iterator it = findSegment(trajectory, time);
  if (it != trajectory.end())
    it->sample(time, state);
  else if (!trajectory.empty())
    trajectory.front().sample(time, state);
  return it;
}

}  // namespace trajectory_interface
