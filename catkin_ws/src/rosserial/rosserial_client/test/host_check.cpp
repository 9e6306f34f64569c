// Host-side check program for test_generated_headers.py: generated messages and the node
// handle compiled with the host's g++ (with AddressSanitizer), driven over stdin/stdout.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vector>
#include <string>

#include "ros/node_handle.h"
#include "rs_test/AllTypes.h"
#include "rs_test/Echo.h"
#include "std_msgs/String.h"

static std::vector<unsigned char> unhex(const char *h)
{
  std::vector<unsigned char> out;
  for (size_t i = 0; h[i] && h[i + 1]; i += 2)
  {
    unsigned v;
    sscanf(h + i, "%2x", &v);
    out.push_back((unsigned char)v);
  }
  return out;
}

static void hex(const unsigned char *b, int n)
{
  for (int i = 0; i < n; i++)
    printf("%02x", b[i]);
  printf("\n");
}

// ---- a fake serial port and clock for the node handle --------------------------------------
struct FakeHardware
{
  static std::vector<unsigned char> in, out;
  static unsigned long ms;
  static size_t pos;
  void init() {}
  int read() { return pos < in.size() ? in[pos++] : -1; }
  void write(uint8_t *data, int length) { out.insert(out.end(), data, data + length); }
  unsigned long time() { return ms; }
};
std::vector<unsigned char> FakeHardware::in, FakeHardware::out;
unsigned long FakeHardware::ms = 0;
size_t FakeHardware::pos = 0;

static int received = 0;
static std::string last;
static void cb(const std_msgs::String &m)
{
  received++;
  last = m.data;
}

static std::vector<unsigned char> frame(int topic, const std::vector<unsigned char> &payload)
{
  std::vector<unsigned char> f = { 0xff, 0xfe, (unsigned char)(payload.size() & 255),
                                   (unsigned char)(payload.size() >> 8) };
  f.push_back(255 - ((f[2] + f[3]) % 256));
  f.push_back(topic & 255);
  f.push_back(topic >> 8);
  int sum = f[5] + f[6];
  for (unsigned char c : payload)
  {
    f.push_back(c);
    sum += c;
  }
  f.push_back(255 - (sum % 256));
  return f;
}

/// fill, serialize, print
static int allTypes()
{
  static unsigned char buf[4096];
  rs_test::AllTypes m;
  m.b = true;
  m.i8 = -8;
  m.u8 = 200;
  m.by = -3;
  m.ch = 'x';
  m.i16 = -1600;
  m.u16 = 60000;
  m.i32 = -320000;
  m.u32 = 4000000000UL;
  m.i64 = -64000000000LL;
  m.u64 = 18000000000000000000ULL;
  m.f32 = 3.25f;
  m.f64 = 1.5;
  m.s = "hello";
  m.t.sec = 1700000000;
  m.t.nsec = 123456789;
  m.d.sec = -5;
  m.d.nsec = 500000000;
  m.header.seq = 7;
  m.header.stamp.sec = 11;
  m.header.stamp.nsec = 22;
  m.header.frame_id = "base";
  m.p.x = 0.5;
  m.p.y = -2.0;
  m.p.z = 1e10;
  m.fixed[0] = 1;
  m.fixed[1] = -2;
  m.fixed[2] = 3;
  float f64s[] = { 0.25f, -3.0f };
  m.f64s_length = 2;
  m.f64s = f64s;
  const char *names[] = { "a", "", "long name" };
  m.names_length = 3;
  m.names = names;
  geometry_msgs::Point pts[2];
  pts[0].x = 1;
  pts[1].z = -1;
  m.points_length = 2;
  m.points = pts;
  uint8_t bytes[] = { 0, 255, 128 };
  m.bytes_length = 3;
  m.bytes = bytes;
  int n = m.serialize(buf);
  printf("%d %d\n", n, m.serializedLength());
  hex(buf, n);
  m.f64s = nullptr;
  m.names = nullptr;
  m.points = nullptr;
  m.bytes = nullptr;
  m.f64s_length = m.names_length = m.points_length = m.bytes_length = 0;
  return 0;
}

/// deserialize argv[2], serialize again
static int roundTrip(int argc, char **argv)
{
  std::vector<unsigned char> in = unhex(argv[2]);
  in.resize(in.size() + 8);
  rs_test::AllTypes m;
  int used = m.deserialize(in.data());
  static unsigned char buf[4096];
  int n = m.serialize(buf);
  printf("%d %d %s %s\n", used, n, m.s, m.names_length > 2 ? m.names[2] : "?");
  hex(buf, n);
  free(m.f64s);
  free(m.names);
  free(m.points);
  free(m.bytes);
  return 0;
}

static int serviceTypes()
{
  rs_test::EchoRequest req;
  rs_test::EchoResponse res;
  printf("%s %s %s %s\n", req.getType(), req.getMD5(), res.getType(), res.getMD5());
  return 0;
}

/// float -> 8 wire bytes, for each argv
static int avrFloat64Out(int argc, char **argv)
{
  for (int i = 2; i < argc; i++)
  {
    unsigned char b[8];
    ros::Msg::serializeAvrFloat64(b, (float)strtod(argv[i], nullptr));
    hex(b, 8);
  }
  return 0;
}

/// 8 wire bytes (hex) -> float bits
static int avrFloat64In(int argc, char **argv)
{
  for (int i = 2; i < argc; i++)
  {
    std::vector<unsigned char> b = unhex(argv[i]);
    float f;
    ros::Msg::deserializeAvrFloat64(b.data(), &f);
    uint32_t u;
    memcpy(&u, &f, 4);
    printf("%08x\n", u);
  }
  return 0;
}

/// negotiation, an oversized frame, then a good one
static int nodeHandle()
{
  ros::NodeHandle_<FakeHardware, 2, 2, 64, 128> nh;  // 64-byte input, 128-byte output
  std_msgs::String s;
  ros::Publisher pub("chatter", &s);
  ros::Subscriber<std_msgs::String> sub("words", cb);
  nh.initNode();
  nh.advertise(pub);
  nh.subscribe(sub);
  FakeHardware::out.clear();
  FakeHardware::in = frame(0, {});  // topic request
  nh.spinOnce();
  printf("configured %d\n", nh.connected());
  hex(FakeHardware::out.data(), FakeHardware::out.size());
  // a frame larger than the 64-byte input buffer, then a good one on the subscriber id
  std::vector<unsigned char> big(300, 'A');
  std::vector<unsigned char> in = frame(100, big);
  std::vector<unsigned char> good = frame(100, { 5, 0, 0, 0, 'h', 'e', 'l', 'l', 'o' });
  in.insert(in.end(), good.begin(), good.end());
  FakeHardware::in = in;
  FakeHardware::pos = 0;
  FakeHardware::ms += 1;
  nh.spinOnce();
  printf("received %d %s\n", received, last.c_str());
  // a publish larger than the output buffer is refused, nothing past the buffer written
  std::string longtext(200, 'z');
  s.data = longtext.c_str();
  FakeHardware::out.clear();
  printf("publish %d\n", pub.publish(&s));
  s.data = "ok";
  printf("publish %d\n", pub.publish(&s));
  return 0;
}

int main(int argc, char **argv)
{
  if (argc < 2)
    return 2;
  std::string mode = argv[1];
  if (mode == "alltypes")
    return allTypes();
  if (mode == "roundtrip")
    return roundTrip(argc, argv);
  if (mode == "srv")
    return serviceTypes();
  if (mode == "avr64")
    return avrFloat64Out(argc, argv);
  if (mode == "avr64in")
    return avrFloat64In(argc, argv);
  if (mode == "nodehandle")
    return nodeHandle();
  return 2;
}
