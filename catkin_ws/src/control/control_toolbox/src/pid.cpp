#include <control_toolbox/pid.h>

#include <algorithm>
#include <cmath>

#include <ros/console.h>

namespace control_toolbox
{
namespace
{
const char* const DEFAULT_NAMESPACE = "pid";

bool finite(double value) { return !std::isnan(value) && !std::isinf(value); }
}  // namespace

Pid::Pid(double p, double i, double d, double i_max, double i_min, bool antiwindup)
{
  setGains(p, i, d, i_max, i_min, antiwindup);
  reset();
}

Pid::Pid(const Pid& source)
{
  gains_buffer_ = source.gains_buffer_;
  reset();
}

Pid& Pid::operator=(const Pid& source)
{
  if (this == &source)
    return *this;
  gains_buffer_ = source.gains_buffer_;
  reset();
  return *this;
}

Pid::~Pid() = default;

void Pid::initPid(double p, double i, double d, double i_max, double i_min, const ros::NodeHandle& /*node*/)
{
  initPid(p, i, d, i_max, i_min);
  ros::NodeHandle nh(DEFAULT_NAMESPACE);
  initDynamicReconfig(nh);
}

void Pid::initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup,
                  const ros::NodeHandle& /*node*/)
{
  initPid(p, i, d, i_max, i_min, antiwindup);
  ros::NodeHandle nh(DEFAULT_NAMESPACE);
  initDynamicReconfig(nh);
}

void Pid::initPid(double p, double i, double d, double i_max, double i_min, bool antiwindup)
{
  setGains(p, i, d, i_max, i_min, antiwindup);
  reset();
}

bool Pid::initParam(const std::string& prefix, const bool quiet)
{
  ros::NodeHandle nh(prefix);
  return init(nh, quiet);
}

bool Pid::init(const ros::NodeHandle& node, const bool quiet)
{
  ros::NodeHandle nh(node);
  Gains gains;

  if (!nh.getParam("p", gains.p_gain_))
  {
    if (!quiet)
      ROS_ERROR("No p gain specified for pid.  Namespace: %s", nh.getNamespace().c_str());
    return false;
  }
  nh.param("i", gains.i_gain_, 0.0);
  nh.param("d", gains.d_gain_, 0.0);

  // i_clamp sets a symmetric window; i_clamp_min / i_clamp_max override one side each
  double i_clamp = 0.0;
  nh.param("i_clamp", i_clamp, 0.0);
  gains.i_max_ = std::abs(i_clamp);
  gains.i_min_ = -std::abs(i_clamp);
  if (nh.hasParam("i_clamp_min"))
  {
    nh.param("i_clamp_min", gains.i_min_, gains.i_min_);
    gains.i_min_ = -std::abs(gains.i_min_);
  }
  if (nh.hasParam("i_clamp_max"))
  {
    nh.param("i_clamp_max", gains.i_max_, gains.i_max_);
    gains.i_max_ = std::abs(gains.i_max_);
  }
  nh.param("antiwindup", gains.antiwindup_, false);
  nh.param("publish_state", publish_state_, false);

  if (publish_state_)
  {
    state_publisher_ = std::make_shared<realtime_tools::RealtimePublisher<control_msgs::PidState>>();
    state_publisher_->init(nh, "state", 1);
  }

  setGains(gains);
  reset();
  initDynamicReconfig(nh);
  return true;
}

void Pid::initDynamicReconfig(ros::NodeHandle& node)
{
  ROS_DEBUG_STREAM_NAMED("pid", "Initializing dynamic reconfigure in namespace " << node.getNamespace());
  param_reconfig_server_ = std::make_shared<DynamicReconfigServer>(param_reconfig_mutex_, node);
  dynamic_reconfig_initialized_ = true;

  // the server starts from the parameter server's values: show ours instead, then listen
  updateDynamicReconfig();
  param_reconfig_server_->setCallback([this](control_toolbox::ParametersConfig& config, uint32_t level)
                                      { dynamicReconfigCallback(config, level); });
}

void Pid::reset()
{
  p_error_last_ = 0.0;
  p_error_ = 0.0;
  i_error_ = 0.0;
  d_error_ = 0.0;
  cmd_ = 0.0;
}

void Pid::getGains(double& p, double& i, double& d, double& i_max, double& i_min)
{
  bool antiwindup = false;
  getGains(p, i, d, i_max, i_min, antiwindup);
}

void Pid::getGains(double& p, double& i, double& d, double& i_max, double& i_min, bool& antiwindup)
{
  const Gains gains = *gains_buffer_.readFromRT();
  p = gains.p_gain_;
  i = gains.i_gain_;
  d = gains.d_gain_;
  i_max = gains.i_max_;
  i_min = gains.i_min_;
  antiwindup = gains.antiwindup_;
}

Pid::Gains Pid::getGains() { return *gains_buffer_.readFromRT(); }

void Pid::setGains(double p, double i, double d, double i_max, double i_min, bool antiwindup)
{
  setGains(Gains(p, i, d, i_max, i_min, antiwindup));
}

void Pid::setGains(const Gains& gains)
{
  gains_buffer_.writeFromNonRT(gains);
  updateDynamicReconfig(gains);
}

void Pid::updateDynamicReconfig()
{
  if (!dynamic_reconfig_initialized_)
    return;
  control_toolbox::ParametersConfig config;
  getGains(config.p, config.i, config.d, config.i_clamp_max, config.i_clamp_min, config.antiwindup);
  updateDynamicReconfig(config);
}

void Pid::updateDynamicReconfig(Gains gains_config)
{
  if (!dynamic_reconfig_initialized_)
    return;
  control_toolbox::ParametersConfig config;
  config.p = gains_config.p_gain_;
  config.i = gains_config.i_gain_;
  config.d = gains_config.d_gain_;
  config.i_clamp_max = gains_config.i_max_;
  config.i_clamp_min = gains_config.i_min_;
  config.antiwindup = gains_config.antiwindup_;
  updateDynamicReconfig(config);
}

void Pid::updateDynamicReconfig(control_toolbox::ParametersConfig config)
{
  if (!dynamic_reconfig_initialized_)
    return;
  boost::recursive_mutex::scoped_lock lock(param_reconfig_mutex_);
  param_reconfig_server_->updateConfig(config);
}

void Pid::dynamicReconfigCallback(control_toolbox::ParametersConfig& config, uint32_t /*level*/)
{
  ROS_DEBUG_STREAM_NAMED("pid", "Dynamics reconfigure callback recieved.");
  setGains(config.p, config.i, config.d, config.i_clamp_max, config.i_clamp_min, config.antiwindup);
}

double Pid::computeCommand(double error, ros::Duration dt)
{
  if (dt == ros::Duration(0.0) || !finite(error))
    return 0.0;

  double error_dot = d_error_;
  if (dt.toSec() > 0.0)
  {
    error_dot = (error - p_error_last_) / dt.toSec();
    p_error_last_ = error;
  }
  return computeCommand(error, error_dot, dt);
}

double Pid::updatePid(double error, ros::Duration dt) { return -computeCommand(error, dt); }

double Pid::computeCommand(double error, double error_dot, ros::Duration dt)
{
  const Gains gains = *gains_buffer_.readFromRT();

  p_error_ = error;  // set point - state
  d_error_ = error_dot;

  if (dt == ros::Duration(0.0) || !finite(error) || !finite(error_dot))
    return 0.0;

  const double p_term = gains.p_gain_ * p_error_;

  i_error_ += dt.toSec() * p_error_;
  if (gains.antiwindup_ && gains.i_gain_ != 0.0)
  {
    // bound the integral itself so that i * integral stays within [i_min, i_max]
    const double a = gains.i_min_ / gains.i_gain_;
    const double b = gains.i_max_ / gains.i_gain_;
    i_error_ = std::clamp(i_error_, std::min(a, b), std::max(a, b));
  }
  double i_term = gains.i_gain_ * i_error_;
  if (!gains.antiwindup_)
    i_term = std::clamp(i_term, std::min(gains.i_min_, gains.i_max_), gains.i_max_);

  const double d_term = gains.d_gain_ * d_error_;
  cmd_ = p_term + i_term + d_term;

  if (publish_state_ && state_publisher_ && state_publisher_->trylock())
  {
    control_msgs::PidState& msg = state_publisher_->msg_;
    msg.header.stamp = ros::Time::now();
    msg.timestep = dt;
    msg.error = error;
    msg.error_dot = error_dot;
    msg.p_error = p_error_;
    msg.i_error = i_error_;
    msg.d_error = d_error_;
    msg.p_term = p_term;
    msg.i_term = i_term;
    msg.d_term = d_term;
    msg.i_max = gains.i_max_;
    msg.i_min = gains.i_min_;
    msg.output = cmd_;
    state_publisher_->unlockAndPublish();
  }
  return cmd_;
}

double Pid::updatePid(double error, double error_dot, ros::Duration dt)
{
  return -computeCommand(error, error_dot, dt);
}

void Pid::setCurrentCmd(double cmd) { cmd_ = cmd; }

double Pid::getCurrentCmd() { return cmd_; }

double Pid::getDerivativeError() { return d_error_; }

void Pid::getCurrentPIDErrors(double* pe, double* ie, double* de)
{
  *pe = p_error_;
  *ie = i_error_;
  *de = d_error_;
}

void Pid::printValues()
{
  const Gains gains = getGains();
  ROS_INFO_STREAM_NAMED("pid", "Current Values of PID Class:\n"
                                   << "  P Gain: " << gains.p_gain_ << "\n"
                                   << "  I Gain: " << gains.i_gain_ << "\n"
                                   << "  D Gain: " << gains.d_gain_ << "\n"
                                   << "  I_Max:  " << gains.i_max_ << "\n"
                                   << "  I_Min:  " << gains.i_min_ << "\n"
                                   << "  Antiwindup:  " << gains.antiwindup_ << "\n"
                                   << "  P_Error_Last: " << p_error_last_ << "\n"
                                   << "  P_Error:      " << p_error_ << "\n"
                                   << "  I_Error:       " << i_error_ << "\n"
                                   << "  D_Error:      " << d_error_ << "\n"
                                   << "  Command:      " << cmd_);
}

}  // namespace control_toolbox
