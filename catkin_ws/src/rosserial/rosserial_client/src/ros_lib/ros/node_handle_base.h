// rosserial client library (re-implementation): what publishers and service clients need of
// a node handle, independent of its template parameters.
#ifndef ROS_NODE_HANDLE_BASE_H_
#define ROS_NODE_HANDLE_BASE_H_

#include "ros/msg.h"

namespace ros
{
class NodeHandleBase_
{
public:
  virtual ~NodeHandleBase_() {}
  virtual int publish(int id, const Msg *msg) = 0;
  virtual int spinOnce() = 0;
  virtual bool connected() = 0;
};
}  // namespace ros

#endif
