// rosserial_server (re-implementation): what the device asks of the host (time, parameters,
// log lines) and the ~require check of the topics it set up; the rest of Session is in
// session.cpp.
#include "rosserial_server/session.h"

#include <rosserial_msgs/Log.h>
#include <rosserial_msgs/RequestParam.h>
#include <std_msgs/Time.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include "session_codec.h"

namespace rosserial_server
{

// The topic names of `param_name` (a list of strings), resolved; false with an error line when
// it is not such a list. A missing parameter is an empty list.
static bool requiredTopics(const ros::NodeHandle& nh, const std::string& param_name, std::vector<std::string>& out)
{
  XmlRpc::XmlRpcValue list;
  if (!ros::param::get(param_name, list))
    return true;
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray)
  {
    ROS_ERROR_ONCE("%s must be a list of topic names", param_name.c_str());
    return false;
  }
  for (int i = 0; i < list.size(); ++i)
  {
    if (list[i].getType() != XmlRpc::XmlRpcValue::TypeString)
    {
      ROS_ERROR_ONCE("%s must be a list of topic names (item %d is not a string)", param_name.c_str(), i);
      return false;
    }
    out.push_back(nh.resolveName(static_cast<std::string>(list[i])));
  }
  return true;
}

template <typename M>
static bool allPresent(const ros::NodeHandle& nh, const std::vector<std::string>& required, const M& entries)
{
  for (const std::string& topic : required)
  {
    bool found = false;
    for (const auto& kv : entries)
      found = found || nh.resolveName(kv.first) == topic;
    if (!found)
      return false;
  }
  return true;
}

void Session::checkRequiredTopics()
{
  require_check_pending_ = false;
  if (!ros::param::has("~require"))
    return;
  std::vector<std::string> pubs, subs;
  if (!requiredTopics(nh_, "~require/publishers", pubs) || !requiredTopics(nh_, "~require/subscribers", subs))
    return;
  if (!allPresent(nh_, pubs, publishers_) || !allPresent(nh_, subs, subscribers_))
  {
    ROS_WARN(
        "Connected client failed to establish the publishers and subscribers dictated by "
        "require parameter. Re-requesting topics.");
    requestTopics();
  }
}

void Session::handleTimeRequest()
{
  std_msgs::Time t;
  t.data = ros::Time::now();
  send(rosserial_msgs::TopicInfo::ID_TIME, encode(t));
  if (!synced_)
    ROS_INFO("Connected to the device on %s", stream_->name().c_str());
  synced_ = true;
}

void Session::handleParameterRequest(const std::vector<uint8_t>& payload)
{
  const rosserial_msgs::RequestParamRequest req = decode<rosserial_msgs::RequestParamRequest>(payload);
  XmlRpc::XmlRpcValue value;
  if (!ros::param::get(req.name, value))  // relative to the node, "~x" = its private x
  {
    ROS_ERROR("Parameter %s does not exist", req.name.c_str());
    return;
  }
  rosserial_msgs::RequestParamResponse res;
  std::vector<XmlRpc::XmlRpcValue> items;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeArray)
    for (int i = 0; i < value.size(); ++i)
      items.push_back(value[i]);
  else if (value.getType() == XmlRpc::XmlRpcValue::TypeStruct)
  {
    ROS_ERROR("Cannot send param %s because it is a dictionary", req.name.c_str());
    return;
  }
  else
    items.push_back(value);
  int kind = -1;
  for (auto& v : items)
  {
    int k;
    switch (v.getType())
    {
      case XmlRpc::XmlRpcValue::TypeBoolean:
        k = 0;
        res.ints.push_back(static_cast<bool>(v) ? 1 : 0);
        break;
      case XmlRpc::XmlRpcValue::TypeInt:
        k = 0;
        res.ints.push_back(static_cast<int>(v));
        break;
      case XmlRpc::XmlRpcValue::TypeDouble:
        k = 1;
        res.floats.push_back(static_cast<float>(static_cast<double>(v)));
        break;
      case XmlRpc::XmlRpcValue::TypeString:
        k = 2;
        res.strings.push_back(static_cast<std::string>(v));
        break;
      default:
        ROS_ERROR("Cannot send param %s: values of this type are not supported", req.name.c_str());
        return;
    }
    if (kind >= 0 && k != kind)
    {
      ROS_ERROR("All Paramers in the list %s must be of the same type", req.name.c_str());
      return;
    }
    kind = k;
  }
  send(rosserial_msgs::TopicInfo::ID_PARAMETER_REQUEST, encode(res));
}

void Session::handleLog(const std::vector<uint8_t>& payload)
{
  const rosserial_msgs::Log m = decode<rosserial_msgs::Log>(payload);
  switch (m.level)
  {
    case rosserial_msgs::Log::ROSDEBUG:
      ROS_DEBUG("%s", m.msg.c_str());
      break;
    case rosserial_msgs::Log::INFO:
      ROS_INFO("%s", m.msg.c_str());
      break;
    case rosserial_msgs::Log::WARN:
      ROS_WARN("%s", m.msg.c_str());
      break;
    case rosserial_msgs::Log::ERROR:
      ROS_ERROR("%s", m.msg.c_str());
      break;
    case rosserial_msgs::Log::FATAL:
      ROS_FATAL("%s", m.msg.c_str());
      break;
    default:
      ROS_INFO("%s", m.msg.c_str());
  }
}

}  // namespace rosserial_server
