// Re-implementation of ros_control's joint_limits_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <exception>
#include <string>

namespace joint_limits_interface
{
/// Thrown when a limits handle cannot be built (missing limits) or a handle is not registered.
class JointLimitsInterfaceException : public std::exception
{
public:
  explicit JointLimitsInterfaceException(const std::string& message) : msg_(message) {}
  const char* what() const noexcept override { return msg_.c_str(); }

private:
  std::string msg_;
};

}  // namespace joint_limits_interface
