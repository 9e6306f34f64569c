// rosserial_arduino (re-implementation): a NodeHandle over TCP, for Wi-Fi boards (ESP8266,
// ESP32: WiFiClient) and Ethernet shields (EthernetClient). ros.h picks it on ESP8266/ESP32 or
// when ROSSERIAL_ARDUINO_TCP is defined before including it. As the original, the class is
// named ArduinoHardware:
//   nh.getHardware()->setConnection(server_ip, 11411);   // before nh.initNode()
// The host side is rosserial_server's socket_node (or `serial_node.py tcp`) on port 11411.
// A lost connection is reopened by read() (called from spinOnce()).
#ifndef ROS_ARDUINO_TCP_HARDWARE_H_
#define ROS_ARDUINO_TCP_HARDWARE_H_

#include <Arduino.h>
#if defined(ESP8266)
#include <ESP8266WiFi.h>
#define ROSSERIAL_TCP_CLIENT WiFiClient
#define ROSSERIAL_NETWORK WiFi
#elif defined(ESP32)
#include <WiFi.h>
#define ROSSERIAL_TCP_CLIENT WiFiClient
#define ROSSERIAL_NETWORK WiFi
#else
#include <SPI.h>
#include <Ethernet.h>
#define ROSSERIAL_TCP_CLIENT EthernetClient
#define ROSSERIAL_NETWORK Ethernet
#endif

class ArduinoHardware
{
public:
  ArduinoHardware() : server_(), port_(11411) {}

  // The rosserial server to connect to (rosserial_server socket_node's ~port, default 11411).
  void setConnection(IPAddress &server, int port = 11411)
  {
    server_ = server;
    port_ = port;
  }

  IPAddress getLocalIP() { return ROSSERIAL_NETWORK.localIP(); }

  void init() { connect(); }

  int read()
  {
    if (tcp_.connected())
      return tcp_.read();  // -1 when nothing is waiting
    connect();             // the server went away or restarted: try again
    return -1;
  }

  void write(const uint8_t *data, int length)
  {
    if (tcp_.connected())
      tcp_.write(data, length);
  }

  unsigned long time() { return millis(); }

protected:
  void connect()
  {
    if (tcp_.connect(server_, port_))
    {
#if defined(ESP8266) || defined(ESP32)
      tcp_.setNoDelay(true);  // a frame goes out at once, not after Nagle's delay
#endif
    }
  }

  ROSSERIAL_TCP_CLIENT tcp_;
  IPAddress server_;
  uint16_t port_;
};

#endif
