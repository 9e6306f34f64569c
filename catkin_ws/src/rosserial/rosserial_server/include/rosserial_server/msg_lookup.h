// rosserial_server (re-implementation): what a device's declared types are, looked up from the
// messages' Python modules (genpy), as the original's msg_lookup: md5 sums and the full
// definition a publisher's connection header carries (rosbag needs it).
#ifndef ROSSERIAL_SERVER_MSG_LOOKUP_H
#define ROSSERIAL_SERVER_MSG_LOOKUP_H

#include <string>

namespace rosserial_server
{

struct MsgInfo
{
  std::string md5sum;
  std::string full_text;
};

struct ServiceInfo
{
  std::string md5sum;
  std::string request_md5sum;
  std::string response_md5sum;
};

// Throws std::runtime_error naming the type when it cannot be loaded. Thread safe.
const MsgInfo lookupMessage(const std::string& message_type);
const ServiceInfo lookupService(const std::string& service_type);

// Start the interpreter and import roslib.message in a background thread, so the first device's
// negotiation does not wait for it (a device's getParam() gives up after 1 s).
void warmUpLookups();

}  // namespace rosserial_server

#endif
