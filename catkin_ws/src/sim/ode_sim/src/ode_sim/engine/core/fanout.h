// Fanout: the newest of a stream of small frames, sent to a set of stream sockets by a thread
// of its own, so that the thread producing the frames (the simulation loop publishing /clock)
// spends no system calls on them and runs on while the frames go out on another core.
//
// - Publish() replaces a frame the thread has not yet taken (the subscribers get the newest
//   value; none waits for a slow one) and wakes the thread.
// - A socket whose buffer is full (a subscriber that reads nothing) misses that frame whole.
// - A frame sent in part is completed (waiting up to kPartialTimeoutMs for room), so the
//   stream's framing holds; a socket that fails, or stays full past that, is shut down and
//   reported by TakeDead() (its owner ends the connection, as a failed write does).
// - Add() dup()s the socket: the thread never sends to a descriptor its owner has closed.
// No ROS here: the frames are bytes (ode_sim.ros.plugins.rosio gives it /clock's TCPROS frames).
#ifndef ODE_SIM_ENGINE_CORE_FANOUT_H_
#define ODE_SIM_ENGINE_CORE_FANOUT_H_

#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace ode_sim {

class Fanout {
 public:
  static constexpr int kPartialTimeoutMs = 1000;

  Fanout();
  ~Fanout();
  Fanout(const Fanout&) = delete;
  Fanout& operator=(const Fanout&) = delete;

  // Sends later frames to (a duplicate of) the stream socket fd; returns a handle, or -1 with
  // errno set when fd cannot be duplicated.
  int Add(int fd);
  // Stops sending to a handle (its duplicate is closed by the thread); unknown handles are
  // ignored.
  void Remove(int handle);
  // The frame to send next to every socket (replacing one not yet taken).
  void Publish(const std::string& frame);
  // Handles whose socket failed since the last call (already removed).
  std::vector<int> TakeDead();
  // Blocks until every frame published so far has been sent or dropped (for tests).
  void Flush();
  // Stops the thread and closes every duplicate (the destructor does it too).
  void Close();

  uint64_t sent() const;     // frames written whole to a socket
  uint64_t dropped() const;  // frames a full socket missed
  size_t size() const;       // sockets sent to

 private:
  enum class Result { kSent, kDropped, kBroken };
  void Loop();
  static Result Send(int fd, const std::string& frame);

  mutable std::mutex mu_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::string pending_;
  bool has_pending_ = false;
  bool busy_ = false;
  bool stop_ = false;
  std::map<int, int> fds_;     // handle -> our duplicate
  std::vector<int> to_close_;  // duplicates of removed handles (closed by the thread)
  std::vector<int> dead_;
  int next_handle_ = 1;
  uint64_t sent_ = 0;
  uint64_t dropped_ = 0;
  std::thread thread_;
};

}  // namespace ode_sim

#endif  // ODE_SIM_ENGINE_CORE_FANOUT_H_
