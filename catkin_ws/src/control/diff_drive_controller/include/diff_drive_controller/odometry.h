// Odometry of a differential drive (re-implementation of diff_drive_controller/odometry.h).
// Depends only on ros::Time: integrates wheel positions (or commanded velocities in open loop)
// into a planar pose, and estimates body velocities with a rolling mean.
#pragma once

#include <cstddef>
#include <functional>

#include <ros/time.h>

#include <diff_drive_controller/rolling_mean_accumulator.h>

namespace diff_drive_controller
{

class Odometry
{
public:
  /// (linear [m], angular [rad]) displacement of one step
  typedef std::function<void(double, double)> IntegrationFunction;

  explicit Odometry(std::size_t velocity_rolling_window_size = 10);

  /// Reset the velocity estimates and take `time` as the time of the last update.
  void init(const ros::Time& time);

  /// Integrate from wheel joint positions [rad]. Returns false (pose integrated, velocity not
  /// estimated) when less than 0.1 ms passed since the last update.
  bool update(double left_pos, double right_pos, const ros::Time& time);

  /// Integrate commanded velocities: linear [m/s], angular [rad/s].
  void updateOpenLoop(double linear, double angular, const ros::Time& time);

  double getHeading() const { return heading_; }  ///< [rad]
  double getX() const { return x_; }              ///< [m]
  double getY() const { return y_; }              ///< [m]
  double getLinear() const { return linear_; }    ///< [m/s]
  double getAngular() const { return angular_; }  ///< [rad/s]

  /// Wheel separation [m] and radii [m].
  void setWheelParams(double wheel_separation, double left_wheel_radius, double right_wheel_radius);

  void setVelocityRollingWindowSize(std::size_t velocity_rolling_window_size);

private:
  /// Second order Runge-Kutta step (heading at mid-step).
  void integrateRungeKutta2(double linear, double angular);
  /// Exact arc; falls back to Runge-Kutta 2 for |angular| < 1e-6.
  void integrateExact(double linear, double angular);
  void resetAccumulators();

  ros::Time timestamp_;

  double x_ = 0.0;
  double y_ = 0.0;
  double heading_ = 0.0;
  double linear_ = 0.0;
  double angular_ = 0.0;

  double wheel_separation_ = 0.0;
  double left_wheel_radius_ = 0.0;
  double right_wheel_radius_ = 0.0;

  double left_wheel_old_pos_ = 0.0;   ///< [m] travelled by the left wheel
  double right_wheel_old_pos_ = 0.0;  ///< [m]

  std::size_t velocity_rolling_window_size_;
  RollingMeanAccumulator linear_acc_;
  RollingMeanAccumulator angular_acc_;

  IntegrationFunction integrate_fun_;
};

}  // namespace diff_drive_controller
