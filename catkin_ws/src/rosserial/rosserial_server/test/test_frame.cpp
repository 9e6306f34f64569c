// rosserial_server's frame codec: encode -> parse round trip, resync after garbage, bad
// checksums and versions reported, over-long frames dropped.
#include <gtest/gtest.h>

#include "rosserial_server/frame.h"

using rosserial_server::encodeFrame;
using rosserial_server::FrameParser;

static std::vector<FrameParser::Result> feed(FrameParser& p, const std::vector<uint8_t>& bytes)
{
  std::vector<FrameParser::Result> out;
  for (uint8_t b : bytes)
  {
    FrameParser::Result r = p.feed(b);
    if (r != FrameParser::NONE)
      out.push_back(r);
  }
  return out;
}

TEST(Frame, EncodesAsTheProtocol)
{
  const uint8_t data[] = { 1, 2, 3 };
  std::vector<uint8_t> f = encodeFrame(125, data, 3);
  std::vector<uint8_t> want = { 0xFF, 0xFE, 3, 0, 252, 125, 0, 1, 2, 3, (uint8_t)(255 - (125 + 6) % 256) };
  EXPECT_EQ(f, want);
  std::vector<uint8_t> empty = encodeFrame(0, nullptr, 0);
  EXPECT_EQ(empty, (std::vector<uint8_t>{ 0xFF, 0xFE, 0, 0, 255, 0, 0, 255 }));
}

TEST(Frame, RoundTripAfterGarbage)
{
  FrameParser p;
  std::vector<uint8_t> bytes = { 0x00, 0x12, 0xFF, 0xFF };
  std::vector<uint8_t> payload(300);
  for (size_t i = 0; i < payload.size(); ++i)
    payload[i] = (uint8_t)(i * 7);
  std::vector<uint8_t> f = encodeFrame(101, payload.data(), payload.size());
  bytes.insert(bytes.end(), f.begin(), f.end());
  EXPECT_EQ(feed(p, bytes), std::vector<FrameParser::Result>{ FrameParser::FRAME });
  EXPECT_EQ(p.topicId(), 101);
  EXPECT_EQ(p.payload(), payload);
}

TEST(Frame, ReportsBadFrames)
{
  FrameParser p(100);
  const uint8_t d[] = { 9, 9 };
  std::vector<uint8_t> f = encodeFrame(7, d, 2);
  f.back() ^= 1;
  EXPECT_EQ(feed(p, f), std::vector<FrameParser::Result>{ FrameParser::BAD_CHECKSUM });
  std::vector<uint8_t> g = encodeFrame(7, d, 2);
  g[4] ^= 1;
  EXPECT_EQ(feed(p, g)[0], FrameParser::BAD_LENGTH_CHECKSUM);
  EXPECT_EQ(feed(p, { 0xFF, 0xFD }), std::vector<FrameParser::Result>{ FrameParser::BAD_VERSION });
  EXPECT_EQ(p.badVersion(), 0xFD);
  std::vector<uint8_t> big(200, 1);
  std::vector<uint8_t> h = encodeFrame(100, big.data(), big.size());
  EXPECT_EQ(feed(p, h)[0], FrameParser::TOO_LONG);
  // and the next good frame still parses
  std::vector<uint8_t> ok = encodeFrame(10, d, 2);
  EXPECT_EQ(feed(p, ok).back(), FrameParser::FRAME);
  EXPECT_EQ(p.topicId(), 10);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
