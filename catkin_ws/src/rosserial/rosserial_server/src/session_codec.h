// rosserial_server (re-implementation): ROS message <-> frame payload bytes, for the session's
// source files (not installed).
#ifndef ROSSERIAL_SERVER_SESSION_CODEC_H
#define ROSSERIAL_SERVER_SESSION_CODEC_H

#include <cstdint>
#include <vector>

#include <ros/serialization.h>

namespace rosserial_server
{

template <typename M>
inline M decode(const std::vector<uint8_t>& payload)
{
  M m;
  ros::serialization::IStream s(const_cast<uint8_t*>(payload.data()), (uint32_t)payload.size());
  ros::serialization::deserialize(s, m);
  return m;
}

template <typename M>
inline std::vector<uint8_t> encode(const M& m)
{
  std::vector<uint8_t> out(ros::serialization::serializationLength(m));
  ros::serialization::OStream s(out.data(), (uint32_t)out.size());
  ros::serialization::serialize(s, m);
  return out;
}

}  // namespace rosserial_server

#endif
