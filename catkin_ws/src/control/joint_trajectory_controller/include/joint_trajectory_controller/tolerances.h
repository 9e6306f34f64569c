// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <control_msgs/FollowJointTrajectoryGoal.h>
#include <ros/console.h>
#include <ros/node_handle.h>

namespace joint_trajectory_controller
{
/// Tolerances of one joint's state. A zero tolerance is not enforced.
template <class Scalar>
struct StateTolerances
{
  StateTolerances(Scalar position_tolerance = 0.0, Scalar velocity_tolerance = 0.0, Scalar acceleration_tolerance = 0.0)
    : position(position_tolerance), velocity(velocity_tolerance), acceleration(acceleration_tolerance)
  {
  }

  Scalar position;
  Scalar velocity;
  Scalar acceleration;
};

/// Tolerances of one joint's trajectory: along the path, at the goal, and the goal's time leeway [s].
template <class Scalar>
struct SegmentTolerancesPerJoint
{
  SegmentTolerancesPerJoint() : goal_time_tolerance(0.0) {}

  StateTolerances<Scalar> state_tolerance;
  StateTolerances<Scalar> goal_state_tolerance;
  Scalar goal_time_tolerance;
};

/// Tolerances of every joint of a trajectory.
template <class Scalar>
struct SegmentTolerances
{
  SegmentTolerances(const typename std::vector<Scalar>::size_type& size = 0)
    : state_tolerance(size), goal_state_tolerance(size), goal_time_tolerance(0.0)
  {
  }

  std::vector<StateTolerances<Scalar>> state_tolerance;
  std::vector<StateTolerances<Scalar>> goal_state_tolerance;
  Scalar goal_time_tolerance;
};

/// True if the errors of \p state_error at \p index are within the (enforced, i.e. positive) tolerances.
template <class State>
inline bool checkStateToleranceAt(const State& state_error, const StateTolerances<typename State::Scalar>& tol,
                                  unsigned int index)
{
  using std::abs;
  const bool pos_ok =
      !(tol.position > 0.0) || state_error.position.size() <= index || abs(state_error.position[index]) <= tol.position;
  const bool vel_ok =
      !(tol.velocity > 0.0) || state_error.velocity.size() <= index || abs(state_error.velocity[index]) <= tol.velocity;
  const bool acc_ok = !(tol.acceleration > 0.0) || state_error.acceleration.size() <= index ||
                      abs(state_error.acceleration[index]) <= tol.acceleration;
  return pos_ok && vel_ok && acc_ok;
}

/// True if the error of a one-joint state is within \p tol (\p show_errors: log the violation).
template <class State>
inline bool checkStateTolerancePerJoint(const State& state_error, const StateTolerances<typename State::Scalar>& tol,
                                        bool show_errors = false)
{
  const bool ok = checkStateToleranceAt(state_error, tol, 0);
  if (!ok && show_errors)
    ROS_ERROR_STREAM("Path state tolerances failed: position error " << state_error.position[0] << " (tolerance "
                                                                     << tol.position << ")");
  return ok;
}

/// True if every joint of \p state_error is within its tolerances.
template <class State>
inline bool checkStateTolerance(const State& state_error,
                                const std::vector<StateTolerances<typename State::Scalar>>& tols,
                                bool show_errors = false)
{
  for (unsigned int i = 0; i < tols.size(); ++i)
  {
    if (!checkStateToleranceAt(state_error, tols[i], i))
    {
      if (show_errors)
        ROS_ERROR_STREAM("State tolerances failed for joint " << i << ".");
      return false;
    }
  }
  return true;
}

/**
 * \brief Apply a JointTolerance of a goal to \p tols: a positive value replaces the default, a
 * negative one disables the check (0), zero keeps the default.
 */
template <class Scalar>
inline void updateStateTolerances(const control_msgs::JointTolerance& tol_msg, StateTolerances<Scalar>& tols)
{
  auto apply = [](double value, Scalar& out)
  {
    if (value > 0.0)
      out = static_cast<Scalar>(value);
    else if (value < 0.0)
      out = static_cast<Scalar>(0.0);
  };
  apply(tol_msg.position, tols.position);
  apply(tol_msg.velocity, tols.velocity);
  apply(tol_msg.acceleration, tols.acceleration);
}

/// Apply the path/goal tolerances and goal_time_tolerance of an action goal to \p tols.
template <class Scalar>
inline void updateSegmentTolerances(const control_msgs::FollowJointTrajectoryGoal& goal,
                                    const std::vector<std::string>& joint_names, SegmentTolerances<Scalar>& tols)
{
  for (unsigned int i = 0; i < joint_names.size(); ++i)
  {
    for (const auto& t : goal.path_tolerance)
      if (t.name == joint_names[i])
        updateStateTolerances(t, tols.state_tolerance[i]);
    for (const auto& t : goal.goal_tolerance)
      if (t.name == joint_names[i])
        updateStateTolerances(t, tols.goal_state_tolerance[i]);
  }
  const double gt = goal.goal_time_tolerance.toSec();
  if (gt > 0.0)
    tols.goal_time_tolerance = static_cast<Scalar>(gt);
  else if (gt < 0.0)
    tols.goal_time_tolerance = static_cast<Scalar>(0.0);
}

/**
 * \brief Read the default tolerances from \p nh (the controller's "constraints" namespace):
 * \code
 * constraints:
 *   goal_time: 0.5                   # default 0 (reach the goal by the trajectory's end)
 *   stopped_velocity_tolerance: 0.02 # default 0.01, the velocity part of every goal tolerance
 *   joint1: {trajectory: 0.05, goal: 0.02}   # default 0 (not enforced)
 * \endcode
 */
template <class Scalar>
SegmentTolerances<Scalar> getSegmentTolerances(const ros::NodeHandle& nh, const std::vector<std::string>& joint_names)
{
  const unsigned int n_joints = joint_names.size();
  SegmentTolerances<Scalar> tols(n_joints);
  double goal_time = 0.0, stopped_velocity_tolerance = 0.01;
  nh.param("goal_time", goal_time, 0.0);
  nh.param("stopped_velocity_tolerance", stopped_velocity_tolerance, 0.01);
  tols.goal_time_tolerance = static_cast<Scalar>(goal_time);
  for (unsigned int i = 0; i < n_joints; ++i)
  {
    const std::string prefix = joint_names[i] + "/";
    double trajectory = 0.0, goal = 0.0;
    nh.param(prefix + "trajectory", trajectory, 0.0);
    nh.param(prefix + "goal", goal, 0.0);
    tols.state_tolerance[i].position = static_cast<Scalar>(trajectory);
    tols.goal_state_tolerance[i].position = static_cast<Scalar>(goal);
    tols.goal_state_tolerance[i].velocity = static_cast<Scalar>(stopped_velocity_tolerance);
  }
  return tols;
}

}  // namespace joint_trajectory_controller
