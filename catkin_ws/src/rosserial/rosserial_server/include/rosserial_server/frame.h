// rosserial_server (re-implementation): the rosserial protocol's frames (revision 1).
//   0xFF 0xFE len_lo len_hi len_checksum topic_lo topic_hi payload... checksum
// len_checksum = 255 - (len_lo + len_hi) % 256; checksum = 255 - (topic bytes + payload) % 256.
#ifndef ROSSERIAL_SERVER_FRAME_H
#define ROSSERIAL_SERVER_FRAME_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rosserial_server
{

std::vector<uint8_t> encodeFrame(uint16_t topic_id, const uint8_t* payload, size_t length);

class FrameParser
{
public:
  enum Result
  {
    NONE,                 // byte consumed, no frame yet
    FRAME,                // a complete, valid frame: topicId(), payload()
    BAD_VERSION,          // 0xFF followed by a byte other than 0xFE (a rev 0 device?)
    BAD_LENGTH_CHECKSUM,  // "Wrong checksum for msg length"
    BAD_CHECKSUM,         // "wrong checksum for topic id and msg"
    TOO_LONG              // longer than max_length: dropped
  };

  explicit FrameParser(size_t max_length = 65535) : max_length_(max_length) {}

  Result feed(uint8_t byte);
  void reset() { state_ = SYNC; }
  uint16_t topicId() const { return topic_id_; }
  const std::vector<uint8_t>& payload() const { return payload_; }
  uint8_t badVersion() const { return bad_version_; }

private:
  enum State
  {
    SYNC,
    VERSION,
    LEN_LO,
    LEN_HI,
    LEN_CHK,
    TOPIC_LO,
    TOPIC_HI,
    DATA,
    CHECKSUM
  };
  State state_ = SYNC;
  size_t max_length_;
  uint16_t length_ = 0;
  uint16_t topic_id_ = 0;
  unsigned sum_ = 0;
  uint8_t bad_version_ = 0;
  std::vector<uint8_t> payload_;
};

}  // namespace rosserial_server

#endif
