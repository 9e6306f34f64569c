// ros_lib's time, duration, float64 and subscriber API on the host (gtest), as a program
// written against the original rosserial_client uses it.
#include <gtest/gtest.h>
#include <math.h>

#include "ros/duration.h"
#include "ros/msg.h"
#include "ros/subscriber.h"
#include "ros/time.h"

TEST(Time, AddDurationCarriesNanoseconds)
{
  ros::Time t(1, 500000000);
  t += ros::Duration(1, 600000000);
  EXPECT_EQ(t.sec, 3u);
  EXPECT_EQ(t.nsec, 100000000u);
  ros::Time u = ros::Time(10, 0) + ros::Duration(0, 999999999);
  EXPECT_EQ(u.sec, 10u);
  EXPECT_EQ(u.nsec, 999999999u);
  ros::Time w = ros::Duration(2, 0) + ros::Time(1, 1);
  EXPECT_EQ(w, ros::Time(3, 1));
}

TEST(Time, SubtractDurationWrapsBelowZeroAsUnsigned)
{
  ros::Time t(0, 0);
  t -= ros::Duration(0, 500000000);
  EXPECT_EQ(t.sec, 0xFFFFFFFFu);
  EXPECT_EQ(t.nsec, 500000000u);
  ros::Time u(1, 500000000);
  u -= ros::Duration(1, 600000000);
  EXPECT_EQ(u.sec, 0xFFFFFFFFu);
  EXPECT_EQ(u.nsec, 900000000u);
  ros::Time v = ros::Time(1, 500000000) - ros::Duration(0, 500000000);
  EXPECT_EQ(v, ros::Time(1, 0));
  // large times: no signed overflow
  ros::Time big(0xFFFFFFF0u, 0);
  big += ros::Duration(3, 0);
  EXPECT_EQ(big.sec, 0xFFFFFFF3u);
}

TEST(Time, DifferenceIsADuration)
{
  ros::Duration d = ros::Time(5, 100000000) - ros::Time(3, 900000000);
  EXPECT_EQ(d.sec, 1);
  EXPECT_EQ(d.nsec, 200000000);
  ros::Duration n = ros::Time(3, 900000000) - ros::Time(5, 100000000);
  EXPECT_EQ(n.sec, -2);
  EXPECT_EQ(n.nsec, 800000000);
  EXPECT_NEAR(n.toSec(), -1.2, 1e-9);
}

TEST(Time, Comparisons)
{
  ros::Time a(1, 5), b(1, 6), c(2, 0);
  EXPECT_TRUE(a < b);
  EXPECT_TRUE(b < c);
  EXPECT_TRUE(c > a);
  EXPECT_TRUE(a <= a);
  EXPECT_TRUE(a >= a);
  EXPECT_TRUE(a != b);
  EXPECT_TRUE(a == ros::Time(1, 5));
  EXPECT_FALSE(c < a);
  EXPECT_TRUE(ros::Duration(-1, 0) < ros::Duration(0, 0));
  EXPECT_TRUE(ros::Duration(0, 2) > ros::Duration(0, 1));
  EXPECT_TRUE(ros::Duration(1, 0) == ros::Duration(0, 1000000000));
}

TEST(Time, ConstructorsNormalise)
{
  ros::Time t(1, 2500000000u);
  EXPECT_EQ(t.sec, 3u);
  EXPECT_EQ(t.nsec, 500000000u);
  ros::Duration d(1, -1);
  EXPECT_EQ(d.sec, 0);
  EXPECT_EQ(d.nsec, 999999999);
  ros::Duration e(-1, -1500000000);
  EXPECT_EQ(e.sec, -3);
  EXPECT_EQ(e.nsec, 500000000);
}

TEST(Time, SecondsAndNanoseconds)
{
  ros::Time t;
  t.fromSec(12.25);
  EXPECT_EQ(t.sec, 12u);
  EXPECT_EQ(t.nsec, 250000000u);
  EXPECT_DOUBLE_EQ(t.toSec(), 12.25);
  t.fromNSec(1500000000);
  EXPECT_EQ(t.sec, 1u);
  EXPECT_EQ(t.nsec, 500000000u);
  EXPECT_EQ(t.toNsec(), 1500000000u);
  ros::Duration d;
  d.fromSec(-0.25);
  EXPECT_EQ(d.sec, -1);
  EXPECT_EQ(d.nsec, 750000000);
  EXPECT_DOUBLE_EQ(d.toSec(), -0.25);
  d *= 4.0;
  EXPECT_EQ(d.sec, -1);
  EXPECT_EQ(d.nsec, 0);
  ros::Duration s = ros::Duration(1, 500000000) * 3.0;
  EXPECT_EQ(s, ros::Duration(4, 500000000));
  EXPECT_EQ(-ros::Duration(1, 250000000), ros::Duration(-2, 750000000));
  EXPECT_EQ(ros::Duration(1, 0) - ros::Duration(0, 1), ros::Duration(0, 999999999));
}

TEST(Float64, RoundTripGivesTheSameFloat)
{
  const double cases[] = { 0.0,      10.0,      -50.2, 0.1,    M_PI,        -M_PI, 3.4e38,
                           -3.4e38,  1e-38,     1e-39, -1e-39, 3.14159e-43, 1e-45, 0.99999999999999,
                           INFINITY, -INFINITY, 1e39 };
  for (double c : cases)
  {
    union
    {
      double val;
      unsigned char buffer[8];
    } u;
    ros::Msg::serializeAvrFloat64(u.buffer, (float)c);
    float back = 0;
    ros::Msg::deserializeAvrFloat64(u.buffer, &back);
    EXPECT_EQ((float)c, (float)u.val) << c;
    EXPECT_EQ((float)c, back) << c;
  }
  union
  {
    double val;
    unsigned char buffer[8];
  } n;
  ros::Msg::serializeAvrFloat64(n.buffer, NAN);
  float back = 0;
  ros::Msg::deserializeAvrFloat64(n.buffer, &back);
  EXPECT_TRUE(isnan(n.val));
  EXPECT_TRUE(isnan(back));
}

static bool called;
unsigned char buffer[1];

class PlainMsg  // not a ros::Msg: a subscriber needs only these four members
{
public:
  int serialize(unsigned char *) const { return 0; }
  int deserialize(unsigned char *) { return 0; }
  const char *getType() { return "pkg/Plain"; }
  const char *getMD5() { return "0123"; }
};

class Owner
{
public:
  static void freeCb(const PlainMsg &) { called = true; }
  void memberCb(const PlainMsg &) { called = true; }
};

TEST(Subscriber, FreeAndMemberCallbacks)
{
  ros::Subscriber<PlainMsg> a("t", &Owner::freeCb);
  called = false;
  a.callback(buffer);
  EXPECT_TRUE(called);
  EXPECT_STREQ(a.getMsgType(), "pkg/Plain");
  EXPECT_EQ(a.getEndpointType(), 1);  // rosserial_msgs::TopicInfo::ID_SUBSCRIBER
  Owner o;
  ros::Subscriber<PlainMsg, Owner> b("t", &Owner::memberCb, &o);
  called = false;
  b.callback(buffer);
  EXPECT_TRUE(called);
}

int main(int argc, char **argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
