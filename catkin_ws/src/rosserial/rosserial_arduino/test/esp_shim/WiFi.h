// Host shim: WiFi and WiFiClient (see Arduino.h).
#ifndef SHIM_WIFI_H
#define SHIM_WIFI_H

#include "Arduino.h"

#define WL_CONNECTED 3

class ShimWiFi
{
public:
  void begin(const char*, const char*) {}
  int status() { return WL_CONNECTED; }
  IPAddress localIP() { return IPAddress(127, 0, 0, 1); }
};
static ShimWiFi WiFi;

class WiFiClient
{
public:
  ~WiFiClient() { stop(); }
  int connect(IPAddress, uint16_t)
  {
    stop();
    const char* port = getenv("SHIM_PORT");
    sockaddr_in a;
    memset(&a, 0, sizeof(a));
    a.sin_family = AF_INET;
    a.sin_port = htons(port ? atoi(port) : 11411);
    inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    if (::connect(fd_, (sockaddr*)&a, sizeof(a)) != 0)
    {
      stop();
      return 0;
    }
    fcntl(fd_, F_SETFL, O_NONBLOCK);
    ++connects;
    printf("connected %d\n", connects);
    fflush(stdout);
    return 1;
  }
  void setNoDelay(bool on)
  {
    int v = on ? 1 : 0;
    setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &v, sizeof(v));
  }
  bool connected()
  {
    if (fd_ < 0)
      return false;
    char c;
    ssize_t n = recv(fd_, &c, 1, MSG_PEEK | MSG_DONTWAIT);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK))
    {
      stop();
      return false;
    }
    return true;
  }
  int read()
  {
    unsigned char c;
    return (fd_ >= 0 && ::read(fd_, &c, 1) == 1) ? c : -1;
  }
  size_t write(const uint8_t* data, size_t n)
  {
    size_t done = 0;
    while (fd_ >= 0 && done < n)
    {
      ssize_t w = ::send(fd_, data + done, n - done, MSG_NOSIGNAL);
      if (w > 0)
        done += w;
      else if (errno != EAGAIN)
        break;
    }
    return done;
  }
  void stop()
  {
    if (fd_ >= 0)
      close(fd_);
    fd_ = -1;
  }
  int connects = 0;

private:
  int fd_ = -1;
};

#endif
