// Re-implementation of ros_control's transmission_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <exception>
#include <string>

namespace transmission_interface
{
/// Thrown on invalid transmission parameters (e.g. a zero reduction).
class TransmissionInterfaceException : public std::exception
{
public:
  explicit TransmissionInterfaceException(const std::string& message) : msg_(message) {}
  const char* what() const noexcept override { return msg_.c_str(); }

private:
  std::string msg_;
};

}  // namespace transmission_interface
