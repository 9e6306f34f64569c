#include <diff_drive_controller/speed_limiter.h>

#include <algorithm>

namespace diff_drive_controller
{
namespace
{
/// clamp that tolerates lo > hi (misconfigured limits): the result then is hi, as min(max())
double clamp(double x, double lo, double hi) { return std::min(std::max(x, lo), hi); }

double factor(double out, double in) { return in != 0.0 ? out / in : 1.0; }
}  // namespace

SpeedLimiter::SpeedLimiter(bool has_velocity_limits, bool has_acceleration_limits, bool has_jerk_limits,
                           double min_velocity, double max_velocity, double min_acceleration, double max_acceleration,
                           double min_jerk, double max_jerk)
  : has_velocity_limits(has_velocity_limits)
  , has_acceleration_limits(has_acceleration_limits)
  , has_jerk_limits(has_jerk_limits)
  , min_velocity(min_velocity)
  , max_velocity(max_velocity)
  , min_acceleration(min_acceleration)
  , max_acceleration(max_acceleration)
  , min_jerk(min_jerk)
  , max_jerk(max_jerk)
{
}

double SpeedLimiter::limit(double& v, double v0, double v1, double dt)
{
  const double in = v;
  limit_jerk(v, v0, v1, dt);
  limit_acceleration(v, v0, dt);
  limit_velocity(v);
  return factor(v, in);
}

double SpeedLimiter::limit_velocity(double& v)
{
  const double in = v;
  if (has_velocity_limits)
    v = clamp(v, min_velocity, max_velocity);
  return factor(v, in);
}

double SpeedLimiter::limit_acceleration(double& v, double v0, double dt)
{
  const double in = v;
  if (has_acceleration_limits)
  {
    const double dv = clamp(v - v0, min_acceleration * dt, max_acceleration * dt);
    v = v0 + dv;
  }
  return factor(v, in);
}

double SpeedLimiter::limit_jerk(double& v, double v0, double v1, double dt)
{
  const double in = v;
  if (has_jerk_limits)
  {
    const double dv = v - v0;
    const double dv0 = v0 - v1;
    const double dt2 = 2.0 * dt * dt;
    const double da = clamp(dv - dv0, min_jerk * dt2, max_jerk * dt2);
    v = v0 + dv0 + da;
  }
  return factor(v, in);
}

}  // namespace diff_drive_controller
