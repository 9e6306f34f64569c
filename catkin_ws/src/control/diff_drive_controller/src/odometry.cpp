#include <diff_drive_controller/odometry.h>

#include <cmath>

namespace diff_drive_controller
{

Odometry::Odometry(std::size_t velocity_rolling_window_size)
  : timestamp_(0.0)
  , velocity_rolling_window_size_(velocity_rolling_window_size)
  , linear_acc_(velocity_rolling_window_size)
  , angular_acc_(velocity_rolling_window_size)
  , integrate_fun_([this](double linear, double angular) { integrateExact(linear, angular); })
{
}

void Odometry::init(const ros::Time& time)
{
  resetAccumulators();
  timestamp_ = time;
}

bool Odometry::update(double left_pos, double right_pos, const ros::Time& time)
{
  // distance travelled by each wheel
  const double left_wheel_cur_pos = left_pos * left_wheel_radius_;
  const double right_wheel_cur_pos = right_pos * right_wheel_radius_;

  const double left_wheel_est_vel = left_wheel_cur_pos - left_wheel_old_pos_;
  const double right_wheel_est_vel = right_wheel_cur_pos - right_wheel_old_pos_;
  left_wheel_old_pos_ = left_wheel_cur_pos;
  right_wheel_old_pos_ = right_wheel_cur_pos;

  const double linear = (right_wheel_est_vel + left_wheel_est_vel) * 0.5;
  const double angular = (right_wheel_est_vel - left_wheel_est_vel) / wheel_separation_;

  integrate_fun_(linear, angular);

  const double dt = (time - timestamp_).toSec();
  if (dt < 0.0001)
    return false;  // too short an interval to estimate a velocity

  timestamp_ = time;
  linear_acc_.accumulate(linear / dt);
  angular_acc_.accumulate(angular / dt);
  linear_ = linear_acc_.getRollingMean();
  angular_ = angular_acc_.getRollingMean();
  return true;
}

void Odometry::updateOpenLoop(double linear, double angular, const ros::Time& time)
{
  linear_ = linear;
  angular_ = angular;
  const double dt = (time - timestamp_).toSec();
  timestamp_ = time;
  integrate_fun_(linear * dt, angular * dt);
}

void Odometry::setWheelParams(double wheel_separation, double left_wheel_radius, double right_wheel_radius)
{
  wheel_separation_ = wheel_separation;
  left_wheel_radius_ = left_wheel_radius;
  right_wheel_radius_ = right_wheel_radius;
}

void Odometry::setVelocityRollingWindowSize(std::size_t velocity_rolling_window_size)
{
  velocity_rolling_window_size_ = velocity_rolling_window_size;
  resetAccumulators();
}

void Odometry::integrateRungeKutta2(double linear, double angular)
{
  const double direction = heading_ + angular * 0.5;
  x_ += linear * std::cos(direction);
  y_ += linear * std::sin(direction);
  heading_ += angular;
}

void Odometry::integrateExact(double linear, double angular)
{
  if (std::fabs(angular) < 1e-6)
  {
    integrateRungeKutta2(linear, angular);
    return;
  }
  const double heading_old = heading_;
  const double r = linear / angular;
  heading_ += angular;
  x_ += r * (std::sin(heading_) - std::sin(heading_old));
  y_ += -r * (std::cos(heading_) - std::cos(heading_old));
}

void Odometry::resetAccumulators()
{
  linear_acc_ = RollingMeanAccumulator(velocity_rolling_window_size_);
  angular_acc_ = RollingMeanAccumulator(velocity_rolling_window_size_);
}

}  // namespace diff_drive_controller
