// rosserial_server (re-implementation): frame encoding and the byte-wise frame parser.
#include "rosserial_server/frame.h"

namespace rosserial_server
{

std::vector<uint8_t> encodeFrame(uint16_t topic_id, const uint8_t* payload, size_t length)
{
  std::vector<uint8_t> out;
  out.reserve(length + 8);
  const uint8_t len_lo = length & 0xFF, len_hi = (length >> 8) & 0xFF;
  const uint8_t t_lo = topic_id & 0xFF, t_hi = (topic_id >> 8) & 0xFF;
  out.push_back(0xFF);
  out.push_back(0xFE);
  out.push_back(len_lo);
  out.push_back(len_hi);
  out.push_back(255 - ((len_lo + len_hi) % 256));
  out.push_back(t_lo);
  out.push_back(t_hi);
  unsigned sum = t_lo + t_hi;
  for (size_t i = 0; i < length; ++i)
  {
    out.push_back(payload[i]);
    sum += payload[i];
  }
  out.push_back(255 - (sum % 256));
  return out;
}

FrameParser::Result FrameParser::feed(uint8_t b)
{
  switch (state_)
  {
    case SYNC:
      if (b == 0xFF)
        state_ = VERSION;
      return NONE;
    case VERSION:
      if (b == 0xFE)
      {
        state_ = LEN_LO;
        return NONE;
      }
      if (b == 0xFF)  // a run of 0xFF: the last one may start the frame
        return NONE;
      state_ = SYNC;
      bad_version_ = b;
      return BAD_VERSION;
    case LEN_LO:
      length_ = b;
      sum_ = b;
      state_ = LEN_HI;
      return NONE;
    case LEN_HI:
      length_ |= (uint16_t)b << 8;
      sum_ += b;
      state_ = LEN_CHK;
      return NONE;
    case LEN_CHK:
      if ((sum_ + b) % 256 != 255)
      {
        state_ = SYNC;
        return BAD_LENGTH_CHECKSUM;
      }
      if (length_ > max_length_)
      {
        state_ = SYNC;
        return TOO_LONG;
      }
      state_ = TOPIC_LO;
      return NONE;
    case TOPIC_LO:
      topic_id_ = b;
      sum_ = b;
      state_ = TOPIC_HI;
      return NONE;
    case TOPIC_HI:
      topic_id_ |= (uint16_t)b << 8;
      sum_ += b;
      payload_.clear();
      payload_.reserve(length_);
      state_ = length_ ? DATA : CHECKSUM;
      return NONE;
    case DATA:
      payload_.push_back(b);
      sum_ += b;
      if (payload_.size() == length_)
        state_ = CHECKSUM;
      return NONE;
    case CHECKSUM:
      state_ = SYNC;
      if ((sum_ + b) % 256 != 255)
        return BAD_CHECKSUM;
      return FRAME;
  }
  state_ = SYNC;
  return NONE;
}

}  // namespace rosserial_server
