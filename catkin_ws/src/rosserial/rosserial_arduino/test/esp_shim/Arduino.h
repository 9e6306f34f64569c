// Host shim of the ESP8266/ESP32 Arduino core, enough to run a rosserial sketch on the host
// against a real rosserial server (tests of ArduinoTcpHardware.h): millis/delay, Serial to
// stdout, IPAddress, WiFi (always connected), WiFiClient on POSIX sockets. Every connection
// goes to 127.0.0.1:$SHIM_PORT (the test's socket_node), whatever address the sketch names.
#ifndef SHIM_ARDUINO_H
#define SHIM_ARDUINO_H

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

inline unsigned long millis()
{
  timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1000UL + t.tv_nsec / 1000000UL;
}
inline void delay(unsigned long ms) { usleep(ms * 1000); }

class IPAddress
{
public:
  IPAddress() : b_{ 0, 0, 0, 0 } {}
  IPAddress(uint8_t a, uint8_t b, uint8_t c, uint8_t d) : b_{ a, b, c, d } {}
  std::string toString() const
  {
    char s[20];
    snprintf(s, sizeof(s), "%u.%u.%u.%u", b_[0], b_[1], b_[2], b_[3]);
    return s;
  }

private:
  uint8_t b_[4];
};

class ShimSerial
{
public:
  void begin(long) {}
  void print(const char* s) { fputs(s, stdout); }
  void println(const char* s)
  {
    puts(s);
    fflush(stdout);
  }
  void println(const IPAddress& a) { println(a.toString().c_str()); }
};
static ShimSerial Serial;

#endif
