// ode_sim::Fanout (engine/core/fanout.h) over socket pairs: every socket gets the frames
// whole, a full socket misses a frame whole, a frame larger than the socket's buffer is
// completed while the reader reads, a failed or stuck socket is reported and shut down, and
// the thread sends to its own duplicates only.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <thread>
#include <vector>

#include "fanout.h"

namespace {

struct Pair {
  int writer = -1;
  int reader = -1;
  Pair() {
    int fds[2];
    EXPECT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
    writer = fds[0];
    reader = fds[1];
  }
  ~Pair() {
    if (writer >= 0) close(writer);
    if (reader >= 0) close(reader);
  }
  // everything readable now, without waiting
  std::string Drain() const {
    std::string out;
    char buf[65536];
    ssize_t n;
    while ((n = recv(reader, buf, sizeof(buf), MSG_DONTWAIT)) > 0) out.append(buf, n);
    return out;
  }
  // fills the writer's socket until a send would block; returns the bytes written
  size_t Fill() const {
    const std::string chunk(4096, 'f');
    size_t total = 0;
    ssize_t n;
    while ((n = send(writer, chunk.data(), chunk.size(), MSG_DONTWAIT)) > 0) total += n;
    while ((n = send(writer, "f", 1, MSG_DONTWAIT)) > 0) total += n;  // the last bit of room
    return total;
  }
};

std::string Frame(char c) { return std::string(12, c); }

TEST(Fanout, EverySocketGetsEveryFrameWhenItReads) {
  ode_sim::Fanout fan;
  Pair a, b, c;
  fan.Add(a.writer);
  fan.Add(b.writer);
  fan.Add(c.writer);
  EXPECT_EQ(fan.size(), 3u);
  fan.Publish(Frame('1'));
  fan.Flush();
  fan.Publish(Frame('2'));
  fan.Flush();
  for (const Pair* p : {&a, &b, &c}) EXPECT_EQ(p->Drain(), Frame('1') + Frame('2'));
  EXPECT_EQ(fan.sent(), 6u);
  EXPECT_EQ(fan.dropped(), 0u);
  EXPECT_TRUE(fan.TakeDead().empty());
}

TEST(Fanout, FramesPublishedFasterThanSentKeepTheNewestAndTheFraming) {
  ode_sim::Fanout fan;
  Pair a;
  fan.Add(a.writer);
  for (char ch = 'a'; ch <= 'z'; ++ch) fan.Publish(Frame(ch));
  fan.Flush();
  const std::string got = a.Drain();
  ASSERT_FALSE(got.empty());
  ASSERT_EQ(got.size() % 12, 0u);
  EXPECT_EQ(got.substr(got.size() - 12), Frame('z'));  // the newest always goes out
  for (size_t i = 0; i < got.size(); i += 12) EXPECT_EQ(got.substr(i, 12), Frame(got[i]));
}

TEST(Fanout, AFullSocketMissesAFrameWholeAndTheOthersGetIt) {
  ode_sim::Fanout fan;
  Pair full, fine;
  fan.Add(full.writer);
  fan.Add(fine.writer);
  const size_t filled = full.Fill();
  fan.Publish(Frame('x'));
  fan.Flush();
  EXPECT_EQ(fan.dropped(), 1u);
  EXPECT_EQ(fine.Drain(), Frame('x'));
  const std::string drained = full.Drain();
  EXPECT_EQ(drained.size(), filled);
  EXPECT_EQ(drained.find('x'), std::string::npos);
  fan.Publish(Frame('y'));  // read again: frames arrive again, whole
  fan.Flush();
  EXPECT_EQ(full.Drain(), Frame('y'));
  EXPECT_TRUE(fan.TakeDead().empty());
}

TEST(Fanout, AFrameLargerThanTheBufferIsCompletedWhileTheReaderReads) {
  ode_sim::Fanout fan;
  Pair a;
  fan.Add(a.writer);
  std::string big(1 << 20, '\0');
  for (size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 7);
  std::string got;
  std::thread reader([&] {
    char buf[65536];
    while (got.size() < big.size()) {
      const ssize_t n = recv(a.reader, buf, sizeof(buf), 0);
      if (n <= 0) break;
      got.append(buf, n);
    }
  });
  fan.Publish(big);
  fan.Flush();
  reader.join();
  EXPECT_EQ(got, big);
  EXPECT_EQ(fan.sent(), 1u);
  EXPECT_TRUE(fan.TakeDead().empty());
}

TEST(Fanout, AStuckPartialFrameShutsTheSocketDownAndIsReported) {
  ode_sim::Fanout fan;
  Pair stuck;
  const int h = fan.Add(stuck.writer);
  fan.Publish(std::string(1 << 20, 's'));  // part fits, nobody reads the rest
  fan.Flush();                             // after kPartialTimeoutMs
  EXPECT_EQ(fan.TakeDead(), std::vector<int>{h});
  EXPECT_EQ(fan.size(), 0u);
  // shut down: the reader sees the end of the stream after what arrived
  while (true) {
    char buf[65536];
    const ssize_t n = recv(stuck.reader, buf, sizeof(buf), 0);
    if (n <= 0) {
      EXPECT_EQ(n, 0);
      break;
    }
  }
}

TEST(Fanout, AClosedPeerIsReportedOnceAndTheRestGoOn) {
  ode_sim::Fanout fan;
  Pair gone, fine;
  const int h = fan.Add(gone.writer);
  fan.Add(fine.writer);
  close(gone.reader);
  gone.reader = -1;
  fan.Publish(Frame('1'));
  fan.Flush();
  EXPECT_EQ(fan.TakeDead(), std::vector<int>{h});
  EXPECT_TRUE(fan.TakeDead().empty());
  fan.Publish(Frame('2'));
  fan.Flush();
  EXPECT_EQ(fine.Drain(), Frame('1') + Frame('2'));
}

TEST(Fanout, SendsToItsOwnDuplicateWhichRemoveCloses) {
  ode_sim::Fanout fan;
  Pair a;
  const int h = fan.Add(a.writer);
  close(a.writer);  // the owner closed its descriptor: the duplicate still sends
  a.writer = -1;
  fan.Publish(Frame('d'));
  fan.Flush();
  EXPECT_EQ(a.Drain(), Frame('d'));
  fan.Remove(h);
  fan.Remove(h);  // unknown by now: ignored
  fan.Publish(Frame('e'));
  fan.Flush();  // the round closed the duplicate: the reader sees the end
  char c;
  EXPECT_EQ(recv(a.reader, &c, 1, 0), 0);
  EXPECT_EQ(fan.size(), 0u);
}

TEST(Fanout, CloseEndsTheThreadAndLaterCallsAreHarmless) {
  ode_sim::Fanout fan;
  Pair a;
  fan.Add(a.writer);
  fan.Close();
  fan.Publish(Frame('z'));
  fan.Flush();
  fan.Close();
  EXPECT_EQ(a.Drain(), "");
  EXPECT_EQ(fan.size(), 0u);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
