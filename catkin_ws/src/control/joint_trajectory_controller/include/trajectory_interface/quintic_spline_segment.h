// Re-implementation of ros_controllers' joint_trajectory_controller (ROS 1, 0.21 API) for Debian 12.
#pragma once

#include <array>
#include <stdexcept>
#include <vector>

#include <trajectory_interface/pos_vel_acc_state.h>

namespace trajectory_interface
{
/**
 * \brief A segment between two states: a quintic polynomial when both give positions, velocities
 * and accelerations, a cubic when both give positions and velocities, a linear interpolation
 * otherwise (the order is chosen by what the end points give, as the original).
 *
 * Sampling before the start gives the start position, after the end the end position, both
 * with zero velocity and acceleration (as the original). A zero-duration segment is its start
 * state.
 */
template <class ScalarType>
class QuinticSplineSegment
{
public:
  typedef ScalarType Scalar;
  typedef Scalar Time;
  typedef PosVelAccState<Scalar> State;

  QuinticSplineSegment() = default;

  QuinticSplineSegment(const Time& start_time, const State& start_state, const Time& end_time, const State& end_state)
  {
    init(start_time, start_state, end_time, end_state);
  }

  /// Throws std::invalid_argument if end_time < start_time or the states' sizes disagree.
  void init(const Time& start_time, const State& start_state, const Time& end_time, const State& end_state)
  {
    if (end_time < start_time)
      throw std::invalid_argument("Quintic splines segment can't be constructed: end_time < start_time.");
    const std::size_t dim = start_state.position.size();
    if (dim == 0 || end_state.position.size() != dim)
      throw std::invalid_argument("Can't construct segment from states with empty or different position sizes.");
    const bool has_vel = !start_state.velocity.empty() && !end_state.velocity.empty();
    const bool has_acc = has_vel && !start_state.acceleration.empty() && !end_state.acceleration.empty();
    if ((has_vel && (start_state.velocity.size() != dim || end_state.velocity.size() != dim)) ||
        (has_acc && (start_state.acceleration.size() != dim || end_state.acceleration.size() != dim)))
      throw std::invalid_argument("Can't construct segment from states with mismatched velocity/acceleration sizes.");

    start_time_ = start_time;
    duration_ = end_time - start_time;
    coefs_.assign(dim, Coefs{});
    const Scalar T = duration_;
    for (std::size_t i = 0; i < dim; ++i)
    {
      Coefs& c = coefs_[i];
      c.fill(Scalar(0));
      const Scalar p0 = start_state.position[i], p1 = end_state.position[i];
      if (T == Scalar(0))
      {
        // Degenerate segment: it is its start state.
        c[0] = p0;
        if (has_vel)
          c[1] = start_state.velocity[i];
        if (has_acc)
          c[2] = start_state.acceleration[i] / Scalar(2);
        continue;
      }
      if (has_acc)
      {
        const Scalar v0 = start_state.velocity[i], v1 = end_state.velocity[i];
        const Scalar a0 = start_state.acceleration[i], a1 = end_state.acceleration[i];
        const Scalar T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
        c[0] = p0;
        c[1] = v0;
        c[2] = a0 / Scalar(2);
        c[3] = (Scalar(20) * (p1 - p0) - (Scalar(8) * v1 + Scalar(12) * v0) * T - (Scalar(3) * a0 - a1) * T2) /
               (Scalar(2) * T3);
        c[4] = (Scalar(30) * (p0 - p1) + (Scalar(14) * v1 + Scalar(16) * v0) * T +
                (Scalar(3) * a0 - Scalar(2) * a1) * T2) /
               (Scalar(2) * T4);
        c[5] = (Scalar(12) * (p1 - p0) - Scalar(6) * (v1 + v0) * T - (a0 - a1) * T2) / (Scalar(2) * T5);
      }
      else if (has_vel)
      {
        const Scalar v0 = start_state.velocity[i], v1 = end_state.velocity[i];
        const Scalar T2 = T * T, T3 = T2 * T;
        c[0] = p0;
        c[1] = v0;
        c[2] = (Scalar(3) * (p1 - p0) - (Scalar(2) * v0 + v1) * T) / T2;
        c[3] = (Scalar(2) * (p0 - p1) + (v0 + v1) * T) / T3;
      }
      else
      {
        c[0] = p0;
        c[1] = (p1 - p0) / T;
      }
    }
  }

  /// Fill \p state (resized to size()) with the segment's state at absolute time \p time.
  void sample(const Time& time, State& state) const
  {
    const std::size_t dim = coefs_.size();
    state.position.resize(dim);
    state.velocity.resize(dim);
    state.acceleration.resize(dim);
    const Time t = time - start_time_;
    for (std::size_t i = 0; i < dim; ++i)
    {
      const Coefs& c = coefs_[i];
      if (t < Time(0))
      {
        state.position[i] = c[0];
        state.velocity[i] = Scalar(0);
        state.acceleration[i] = Scalar(0);
        continue;
      }
      if (t > duration_)
      {
        // Past the end: at rest at the end position.
        const Scalar d = duration_;
        state.position[i] = ((((c[5] * d + c[4]) * d + c[3]) * d + c[2]) * d + c[1]) * d + c[0];
        state.velocity[i] = Scalar(0);
        state.acceleration[i] = Scalar(0);
        continue;
      }
      const Scalar s = t;
      state.position[i] = ((((c[5] * s + c[4]) * s + c[3]) * s + c[2]) * s + c[1]) * s + c[0];
      state.velocity[i] =
          (((Scalar(5) * c[5] * s + Scalar(4) * c[4]) * s + Scalar(3) * c[3]) * s + Scalar(2) * c[2]) * s + c[1];
      state.acceleration[i] =
          ((Scalar(20) * c[5] * s + Scalar(12) * c[4]) * s + Scalar(6) * c[3]) * s + Scalar(2) * c[2];
    }
  }

  Time startTime() const { return start_time_; }
  Time endTime() const { return start_time_ + duration_; }
  Time timeFromStart() const { return duration_; }  // kept for older users: the segment's duration
  unsigned int size() const { return static_cast<unsigned int>(coefs_.size()); }

private:
  typedef std::array<Scalar, 6> Coefs;
  std::vector<Coefs> coefs_;
  Time start_time_ = Time(0);
  Time duration_ = Time(0);
};

}  // namespace trajectory_interface
