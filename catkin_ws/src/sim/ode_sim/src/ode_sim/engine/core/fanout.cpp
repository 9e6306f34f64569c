#include "fanout.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <utility>

namespace ode_sim {

Fanout::Fanout() : thread_(&Fanout::Loop, this) {}

Fanout::~Fanout() { Close(); }

int Fanout::Add(int fd) {
  const int copy = fcntl(fd, F_DUPFD_CLOEXEC, 0);
  if (copy < 0) return -1;
  std::lock_guard<std::mutex> lock(mu_);
  if (stop_) {
    close(copy);
    errno = EBADF;
    return -1;
  }
  const int handle = next_handle_++;
  fds_[handle] = copy;
  return handle;
}

void Fanout::Remove(int handle) {
  std::lock_guard<std::mutex> lock(mu_);
  auto it = fds_.find(handle);
  if (it == fds_.end()) return;
  to_close_.push_back(it->second);
  fds_.erase(it);
}

void Fanout::Publish(const std::string& frame) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stop_) return;
    pending_ = frame;
    has_pending_ = true;
  }
  wake_.notify_one();
}

std::vector<int> Fanout::TakeDead() {
  std::lock_guard<std::mutex> lock(mu_);
  return std::exchange(dead_, {});
}

void Fanout::Flush() {
  std::unique_lock<std::mutex> lock(mu_);
  idle_.wait(lock, [this] { return stop_ || (!has_pending_ && !busy_); });
}

void Fanout::Close() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stop_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mu_);
  for (const auto& kv : fds_) close(kv.second);
  fds_.clear();
  for (int fd : to_close_) close(fd);
  to_close_.clear();
  idle_.notify_all();
}

uint64_t Fanout::sent() const {
  std::lock_guard<std::mutex> lock(mu_);
  return sent_;
}

uint64_t Fanout::dropped() const {
  std::lock_guard<std::mutex> lock(mu_);
  return dropped_;
}

size_t Fanout::size() const {
  std::lock_guard<std::mutex> lock(mu_);
  return fds_.size();
}

void Fanout::Loop() {
  std::vector<std::pair<int, int>> targets;
  std::string frame;
  while (true) {
    {
      std::unique_lock<std::mutex> lock(mu_);
      busy_ = false;
      idle_.notify_all();
      wake_.wait(lock, [this] { return stop_ || has_pending_; });
      if (stop_) return;
      frame.swap(pending_);
      has_pending_ = false;
      busy_ = true;
      // closed here, between rounds: never while a send to them may be under way
      for (int fd : to_close_) close(fd);
      to_close_.clear();
      targets.assign(fds_.begin(), fds_.end());
    }
    uint64_t sent = 0, dropped = 0;
    for (const auto& [handle, fd] : targets) {
      const Result r = Send(fd, frame);
      if (r == Result::kSent) {
        ++sent;
      } else if (r == Result::kDropped) {
        ++dropped;
      } else {
        std::lock_guard<std::mutex> lock(mu_);
        auto it = fds_.find(handle);
        if (it != fds_.end()) {  // else Remove() took it: its duplicate is in to_close_
          close(fd);
          fds_.erase(it);
        }
        dead_.push_back(handle);
      }
    }
    std::lock_guard<std::mutex> lock(mu_);
    sent_ += sent;
    dropped_ += dropped;
  }
}

Fanout::Result Fanout::Send(int fd, const std::string& frame) {
  const char* data = frame.data();
  size_t left = frame.size();
  ssize_t n;
  do {
    n = send(fd, data, left, MSG_DONTWAIT | MSG_NOSIGNAL);
  } while (n < 0 && errno == EINTR);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK) return Result::kDropped;
    return Result::kBroken;
  }
  // a part went out: the rest must follow, or the subscriber's stream loses its framing
  while (static_cast<size_t>(n) < left) {
    data += n;
    left -= static_cast<size_t>(n);
    pollfd p{fd, POLLOUT, 0};
    const int ready = poll(&p, 1, kPartialTimeoutMs);
    if (ready < 0 && errno == EINTR) {
      n = 0;
      continue;
    }
    if (ready <= 0 || (p.revents & (POLLERR | POLLHUP | POLLNVAL))) {
      shutdown(fd, SHUT_RDWR);  // the owner's end fails too: the connection ends
      return Result::kBroken;
    }
    do {
      n = send(fd, data, left, MSG_DONTWAIT | MSG_NOSIGNAL);
    } while (n < 0 && errno == EINTR);
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
      shutdown(fd, SHUT_RDWR);
      return Result::kBroken;
    }
    if (n < 0) n = 0;
  }
  return Result::kSent;
}

}  // namespace ode_sim
