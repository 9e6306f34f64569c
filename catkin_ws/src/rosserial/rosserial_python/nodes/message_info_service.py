#!/usr/bin/env python3
"""rosrun rosserial_python message_info_service.py: the services `message_info`
(rosserial_msgs/RequestMessageInfo: type -> md5, definition) and `service_info`
(rosserial_msgs/RequestServiceInfo: service type -> service/request/response md5), as the
original's. rosserial_server's launch files start it as the original's do, but this repository's
C++ rosserial_server looks the types up itself (embedded Python, msg_lookup.cpp) and never calls it."""
import rospy
from rosserial_msgs.srv import (RequestMessageInfo, RequestMessageInfoResponse,
                                RequestServiceInfo, RequestServiceInfoResponse)

from rosserial_python.message_info import MessageInfo


def main():
    rospy.init_node('message_info_service')
    rospy.loginfo('rosserial message_info_service node')
    info = MessageInfo(rospy.logwarn)

    def on_message(req):
        md5, definition = info.message(req.type)
        return RequestMessageInfoResponse(md5=md5, definition=definition)

    def on_service(req):
        return RequestServiceInfoResponse(*info.service(req.service))

    rospy.Service('message_info', RequestMessageInfo, on_message)
    rospy.Service('service_info', RequestServiceInfo, on_service)
    rospy.spin()


if __name__ == '__main__':
    main()
