// Re-implementation of control_toolbox/pid.h (ROS 1 control_toolbox 1.19 API).
//
// A PID controller: command = p*e + i*integral(e) + d*de/dt, with the integral term clamped
// to [i_min, i_max] (or, with antiwindup, the integral itself bounded so that i*integral stays
// inside [i_min, i_max]). Gains are passed to the realtime side through a RealtimeBuffer;
// init(NodeHandle) reads them from the parameter server and serves them with
// dynamic_reconfigure in the same namespace; optionally publishes control_msgs/PidState on
// <namespace>/state.
#pragma once

#include <memory>
#include <string>

#include <boost/thread/recursive_mutex.hpp>
#include <control_msgs/PidState.h>
#include <control_toolbox/ParametersConfig.h>
#include <dynamic_reconfigure/server.h>
#include <realtime_tools/realtime_buffer.h>
#include <realtime_tools/realtime_publisher.h>
#include <ros/duration.h>
#include <ros/node_handle.h>

namespace control_toolbox
{

class Pid
{
public:
  /// Gains and integral limits of a Pid (units: command per unit of error, per error*s, per error/s).
  struct Gains
  {
    Gains(double p, double i, double d, double i_max, double i_min)
      : p_gain_(p), i_gain_(i), d_gain_(d), i_max_(i_max), i_min_(i_min), antiwindup_(false)
    {
    }
    Gains(double p, double i, double d, double i_max, double i_min, bool antiwindup)
      : p_gain_(p), i_gain_(i), d_gain_(d), i_max_(i_max), i_min_(i_min), antiwindup_(antiwindup)
    {
    }
    Gains() = default;

    double p_gain_ = 0.0;
    double i_gain_ = 0.0;
    double d_gain_ = 0.0;
    double i_max_ = 0.0;
    double i_min_ = 0.0;
    bool antiwindup_ = false;
  };

  Pid(double p = 0.0, double i = 0.0, double d = 0.0, double i_max = 0.0, double i_min = -0.0, bool antiwindup = false);
  Pid(const Pid& source);
  Pid& operator=(const Pid& source);
  ~Pid();

  /// Set gains and reset; the NodeHandle variants also start dynamic_reconfigure in "pid".
  void initPid(double p, double i, double d, double i_max, double i_min, const ros::NodeHandle& node);
  void initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup, const ros::NodeHandle& node);
  void initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup = false);

  /// init() in the namespace `prefix`.
  bool initParam(const std::string& prefix, const bool quiet = false);

  /// Read p (required), i, d, i_clamp, i_clamp_min, i_clamp_max, antiwindup, publish_state from
  /// `n`'s namespace; start dynamic_reconfigure there. False (and an ERROR unless quiet) without p.
  bool init(const ros::NodeHandle& n, const bool quiet = false);

  /// Serve the gains with dynamic_reconfigure in `node`'s namespace.
  void initDynamicReconfig(ros::NodeHandle& node);

  /// Zero the errors, the integral and the command.
  void reset();

  void getGains(double& p, double& i, double& d, double& i_max, double& i_min);
  void getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup);
  Gains getGains();

  void setGains(double p, double i, double d, double i_max, double i_min, bool antiwindup = false);
  void setGains(const Gains& gains);

  void updateDynamicReconfig();
  void updateDynamicReconfig(Gains gains_config);
  void updateDynamicReconfig(control_toolbox::ParametersConfig config);
  void dynamicReconfigCallback(control_toolbox::ParametersConfig& config, uint32_t level);

  /// Command for `error` (= set point - state), its derivative taken by finite difference.
  /// Returns 0 (state untouched) for dt == 0 or a NaN/inf error.
  double computeCommand(double error, ros::Duration dt);

  /// Command for `error` and its derivative `error_dot`. Returns 0 for dt == 0 or NaN/inf input.
  double computeCommand(double error, double error_dot, ros::Duration dt);

  /// Deprecated upstream: -computeCommand(...) (error = state - set point convention).
  double updatePid(double p_error, ros::Duration dt);
  double updatePid(double error, double error_dot, ros::Duration dt);

  void setCurrentCmd(double cmd);
  double getCurrentCmd();
  double getDerivativeError();
  void getCurrentPIDErrors(double* pe, double* ie, double* de);

  /// Log gains and state at INFO.
  void printValues();

private:
  using DynamicReconfigServer = dynamic_reconfigure::Server<control_toolbox::ParametersConfig>;

  realtime_tools::RealtimeBuffer<Gains> gains_buffer_;
  std::shared_ptr<realtime_tools::RealtimePublisher<control_msgs::PidState>> state_publisher_;
  bool publish_state_ = false;

  double p_error_last_ = 0.0;  ///< error of the previous computeCommand(error, dt)
  double p_error_ = 0.0;
  double i_error_ = 0.0;  ///< integral of the error [error*s]
  double d_error_ = 0.0;
  double cmd_ = 0.0;

  bool dynamic_reconfig_initialized_ = false;
  std::shared_ptr<DynamicReconfigServer> param_reconfig_server_;
  boost::recursive_mutex param_reconfig_mutex_;
};

}  // namespace control_toolbox
