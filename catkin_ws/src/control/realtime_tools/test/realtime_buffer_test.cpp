#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include <realtime_tools/realtime_box.h>
#include <realtime_tools/realtime_buffer.h>

using realtime_tools::RealtimeBuffer;

struct Command
{
  double lin = 0.0;
  double ang = 0.0;
};

TEST(RealtimeBuffer, DefaultConstructedValue)
{
  RealtimeBuffer<Command> buffer;
  EXPECT_EQ(0.0, buffer.readFromRT()->lin);
  EXPECT_EQ(0.0, buffer.readFromNonRT()->ang);
}

TEST(RealtimeBuffer, WriteIsSeenByBothReaders)
{
  RealtimeBuffer<Command> buffer;
  buffer.writeFromNonRT({ 1.5, -2.0 });
  EXPECT_EQ(1.5, buffer.readFromNonRT()->lin);
  EXPECT_EQ(1.5, buffer.readFromRT()->lin);
  EXPECT_EQ(-2.0, buffer.readFromRT()->ang);
  EXPECT_EQ(1.5, buffer.readFromNonRT()->lin);  // after the swap the non-RT reader sees it too
  buffer.writeFromNonRT({ 3.0, 0.0 });
  EXPECT_EQ(3.0, buffer.readFromRT()->lin);
}

TEST(RealtimeBuffer, InitRTSetsBothCopies)
{
  RealtimeBuffer<int> buffer(7);
  EXPECT_EQ(7, *buffer.readFromRT());
  buffer.writeFromNonRT(8);
  buffer.initRT(3);
  EXPECT_EQ(3, *buffer.readFromRT());
  EXPECT_EQ(3, *buffer.readFromNonRT());
}

TEST(RealtimeBuffer, CopyTakesTheNewestValue)
{
  RealtimeBuffer<int> a(1);
  a.writeFromNonRT(5);
  RealtimeBuffer<int> b(a);
  EXPECT_EQ(5, *b.readFromRT());
  RealtimeBuffer<int> c;
  c = a;
  EXPECT_EQ(5, *c.readFromRT());
}

TEST(RealtimeBuffer, ConcurrentWriterNeverTearsAValue)
{
  RealtimeBuffer<Command> buffer({ 0.0, 0.0 });
  std::atomic<bool> done(false);
  std::thread writer(
      [&]
      {
        for (int i = 1; i <= 20000; ++i)
          buffer.writeFromNonRT({ double(i), -double(i) });
        done = true;
      });
  double last = 0.0;
  while (!done)
  {
    const Command c = *buffer.readFromRT();
    ASSERT_EQ(c.lin, -c.ang);
    ASSERT_GE(c.lin, last);  // values only move forward
    last = c.lin;
  }
  writer.join();
  EXPECT_EQ(20000.0, buffer.readFromRT()->lin);
}

TEST(RealtimeBox, SetGet)
{
  realtime_tools::RealtimeBox<int> box(4);
  int v = 0;
  box.get(v);
  EXPECT_EQ(4, v);
  box.set(9);
  box.get(v);
  EXPECT_EQ(9, v);
}
