// rosserial_arduino (re-implementation): ros::NodeHandle for Arduino boards.
#ifndef _ROS_H_
#define _ROS_H_

#include "ros/node_handle.h"
#if defined(ESP8266) || defined(ESP32) || defined(ROSSERIAL_ARDUINO_TCP)
#include "ArduinoTcpHardware.h"  // Wi-Fi boards / Ethernet shields: rosserial over TCP
#else
#include "ArduinoHardware.h"
#endif

namespace ros
{
#if defined(__AVR_ATmega8__) || defined(__AVR_ATmega168__)
// 1 KB of SRAM: small buffers, few topics
typedef NodeHandle_<ArduinoHardware, 6, 6, 150, 150> NodeHandle;
#elif defined(__AVR_ATmega328P__)
// Uno, Nano: 2 KB of SRAM
typedef NodeHandle_<ArduinoHardware, 25, 25, 280, 280> NodeHandle;
#else
// Mega (ATmega2560) and everything else: the template defaults (25, 25, 512, 512)
typedef NodeHandle_<ArduinoHardware> NodeHandle;
#endif
}  // namespace ros

#endif
