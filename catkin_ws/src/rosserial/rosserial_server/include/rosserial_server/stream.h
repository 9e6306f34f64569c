// rosserial_server (re-implementation): the byte stream a session talks over: a serial port
// (or pty), an accepted TCP socket or a connected UDP socket, all file descriptors.
#ifndef ROSSERIAL_SERVER_STREAM_H
#define ROSSERIAL_SERVER_STREAM_H

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>

namespace rosserial_server
{

class FdStream
{
public:
  FdStream(int fd, const std::string& name) : fd_(fd), name_(name) {}
  ~FdStream();
  FdStream(const FdStream&) = delete;
  FdStream& operator=(const FdStream&) = delete;

  // > 0 bytes read, 0 nothing within timeout_ms, -1 closed / failed
  int read(uint8_t* buf, size_t size, int timeout_ms);
  // whole buffer written (waits while the kernel buffer is full); false once the peer is gone
  bool write(const uint8_t* data, size_t size);
  // after close() every write fails silently (the session ended)
  void close();
  const std::string& name() const { return name_; }

private:
  std::mutex mutex_;
  int fd_;
  bool closed_ = false;
  std::string name_;
};

// Open a serial port (or pty) raw at `baud`; -1 and `error` set when it cannot be opened.
int openSerial(const std::string& port, int baud, std::string& error);

}  // namespace rosserial_server

#endif
