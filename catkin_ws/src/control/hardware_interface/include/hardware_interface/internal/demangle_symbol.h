// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once

#include <cstdlib>
#include <memory>
#include <string>
#include <typeinfo>

#include <cxxabi.h>

namespace hardware_interface
{
namespace internal
{
/// Human-readable name of a mangled C++ symbol ("hardware_interface::EffortJointInterface").
inline std::string demangleSymbol(const char* name)
{
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> res(abi::__cxa_demangle(name, nullptr, nullptr, &status), std::free);
  return (status == 0 && res) ? std::string(res.get()) : std::string(name);
}

template <class T>
std::string demangledTypeName()
{
  return demangleSymbol(typeid(T).name());
}

template <class T>
std::string demangledTypeName(const T& val)
{
  return demangleSymbol(typeid(val).name());
}

}  // namespace internal
}  // namespace hardware_interface
