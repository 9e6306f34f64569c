// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <exception>
#include <string>

namespace hardware_interface
{
/// Thrown on programmer errors: null data pointers, missing handles.
class HardwareInterfaceException : public std::exception
{
public:
  explicit HardwareInterfaceException(const std::string& message) : msg_(message) {}
  const char* what() const noexcept override { return msg_.c_str(); }

private:
  std::string msg_;
};

}  // namespace hardware_interface
