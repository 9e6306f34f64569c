// rosserial_server (re-implementation): file-descriptor streams and serial port set-up.
#include "rosserial_server/stream.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

namespace rosserial_server
{

FdStream::~FdStream() { close(); }

void FdStream::close()
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (!closed_ && fd_ >= 0)
    ::close(fd_);
  closed_ = true;
}

int FdStream::read(uint8_t* buf, size_t size, int timeout_ms)
{
  int fd;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_)
      return -1;
    fd = fd_;
  }
  pollfd p{ fd, POLLIN, 0 };
  int r = ::poll(&p, 1, timeout_ms);
  if (r < 0)
    return errno == EINTR ? 0 : -1;
  if (r == 0)
    return 0;
  if (p.revents & (POLLIN | POLLERR))
  {
    ssize_t n = ::read(fd, buf, size);
    if (n > 0)
      return (int)n;
    // ECONNREFUSED: a connected UDP socket's client is not listening (yet): nothing to read
    if (n < 0 && (errno == EAGAIN || errno == EINTR || errno == ECONNREFUSED))
      return 0;
    return -1;  // 0: end of stream; EIO: the pty's other side closed
  }
  if (p.revents & (POLLHUP | POLLERR | POLLNVAL))
    return -1;
  return 0;
}

bool FdStream::write(const uint8_t* data, size_t size)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (closed_)
    return false;
  size_t done = 0;
  int stalls = 0;
  while (done < size)
  {
    ssize_t n = ::write(fd_, data + done, size - done);
    if (n > 0)
    {
      done += (size_t)n;
      stalls = 0;
      continue;
    }
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0 && errno == ECONNREFUSED)
      return true;  // a UDP client not listening (yet): the datagram is lost, as UDP loses it
    if (n < 0 && errno == EAGAIN)
    {
      pollfd p{ fd_, POLLOUT, 0 };
      if (::poll(&p, 1, 100) == 0 && ++stalls > 50)
        return false;  // 5 s without room: the device stopped reading
      continue;
    }
    return false;
  }
  return true;
}

static speed_t baudConstant(int baud)
{
  switch (baud)
  {
    case 1200:
      return B1200;
    case 2400:
      return B2400;
    case 4800:
      return B4800;
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 576000:
      return B576000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 2000000:
      return B2000000;
    default:
      return 0;
  }
}

int openSerial(const std::string& port, int baud, std::string& error)
{
  const speed_t speed = baudConstant(baud);
  if (!speed)
  {
    error = "unsupported baud rate " + std::to_string(baud);
    return -1;
  }
  int fd = ::open(port.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
  {
    error = std::strerror(errno);
    return -1;
  }
  termios tio;
  if (tcgetattr(fd, &tio) == 0)
  {
    cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD;
    tio.c_cflag &= ~CRTSCTS;
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    cfsetispeed(&tio, speed);
    cfsetospeed(&tio, speed);
    if (tcsetattr(fd, TCSANOW, &tio) != 0)
    {
      error = std::string("cannot configure the port: ") + std::strerror(errno);
      ::close(fd);
      return -1;
    }
  }
  else if (errno != ENOTTY)
  {
    error = std::string("cannot configure the port: ") + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace rosserial_server
