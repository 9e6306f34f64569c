// Velocity / acceleration / jerk limiter of one command axis (re-implementation of
// diff_drive_controller/speed_limiter.h; no ROS).
#pragma once

namespace diff_drive_controller
{

class SpeedLimiter
{
public:
  /// Limits: velocity [m/s or rad/s], acceleration [.../s^2], jerk [.../s^3]; each family is
  /// applied only when its has_*_limits flag is set.
  SpeedLimiter(bool has_velocity_limits = false, bool has_acceleration_limits = false, bool has_jerk_limits = false,
               double min_velocity = 0.0, double max_velocity = 0.0, double min_acceleration = 0.0,
               double max_acceleration = 0.0, double min_jerk = 0.0, double max_jerk = 0.0);

  /// Limit `v` given the previous command v0 and the one before v1, dt [s] apart.
  /// Returns the limiting factor v_out / v_in (1 when v_in is 0).
  double limit(double& v, double v0, double v1, double dt);

  double limit_velocity(double& v);
  double limit_acceleration(double& v, double v0, double dt);
  double limit_jerk(double& v, double v0, double v1, double dt);

  bool has_velocity_limits;
  bool has_acceleration_limits;
  bool has_jerk_limits;

  double min_velocity;
  double max_velocity;
  double min_acceleration;
  double max_acceleration;
  double min_jerk;
  double max_jerk;
};

}  // namespace diff_drive_controller
