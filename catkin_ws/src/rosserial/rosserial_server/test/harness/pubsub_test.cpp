// rosserial_test-style gtest: roscpp and a rosserial client (headers in namespace rosserial)
// in one process, the client connected to socket_node over TCP (~tcp_port) or, with
// ~mode serial, to serial_node through a new pty per test case symlinked at ~port.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <thread>

#include <gtest/gtest.h>
#include "ros/ros.h"
#include "std_msgs/String.h"
#include "std_srvs/Empty.h"

namespace rosserial
{
#include "client_ros.h"
#include "rosserial/std_msgs/String.h"
#include "rosserial/std_srvs/Empty.h"
}  // namespace rosserial

class Fixture : public ::testing::Test
{
protected:
  void SetUp() override
  {
    std::string mode = "socket";
    ros::param::get("~mode", mode);
    if (mode == "serial")
    {
      // a new pty per test case, its slave symlinked at ~port where serial_node looks
      ros::param::get("~port", link_);
      fd_ = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
      ASSERT_GE(fd_, 0);
      ASSERT_EQ(grantpt(fd_), 0);
      ASSERT_EQ(unlockpt(fd_), 0);
      unlink(link_.c_str());
      ASSERT_EQ(symlink(ptsname(fd_), link_.c_str()), 0);
      rosserial::ClientComms::fd = fd_;
      return;
    }
    int port = 11411;
    ros::param::get("~tcp_port", port);
    sockaddr_in a;
    memset(&a, 0, sizeof(a));
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
    for (int i = 0; i < 100; ++i)
    {
      fd_ = socket(AF_INET, SOCK_STREAM, 0);
      if (connect(fd_, (sockaddr*)&a, sizeof(a)) == 0)
        break;
      close(fd_);
      fd_ = -1;
      ros::WallDuration(0.2).sleep();
    }
    ASSERT_GE(fd_, 0);
    fcntl(fd_, F_SETFL, O_NONBLOCK);
    rosserial::ClientComms::fd = fd_;
  }
  void TearDown() override
  {
    if (!link_.empty())
      unlink(link_.c_str());
    close(fd_);
  }
  int fd_ = -1;
  std::string link_;
  rosserial::ros::NodeHandle client_nh;
  ros::NodeHandle nh;
};

struct Got
{
  int n = 0;
  std::string last;
  void cb(const std_msgs::String::ConstPtr& m)
  {
    ++n;
    last = m->data;
  }
};

TEST_F(Fixture, single_publish)
{
  rosserial::std_msgs::String msg;
  rosserial::ros::Publisher pub("chatter", &msg);
  client_nh.advertise(pub);
  client_nh.initNode();
  char s[] = "from-rosserial-client";
  msg.data = s;
  Got got;
  ros::Subscriber sub = nh.subscribe("chatter", 1, &Got::cb, &got);
  for (int i = 0; i < 600 && got.n == 0; ++i)
  {
    pub.publish(&msg);
    client_nh.spinOnce();
    ros::spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_GT(got.n, 0);
  EXPECT_EQ(got.last, s);
}

static int sub_count = 0;
static std::string sub_last;
static void onString(const rosserial::std_msgs::String& m)
{
  ++sub_count;
  sub_last = m.data;
}

TEST_F(Fixture, single_subscribe)
{
  rosserial::ros::Subscriber<rosserial::std_msgs::String> sub("chatter_in", &onString);
  client_nh.subscribe(sub);
  client_nh.initNode();
  ros::Publisher pub = nh.advertise<std_msgs::String>("chatter_in", 1);
  std_msgs::String m;
  m.data = "to-rosserial-client";
  for (int i = 0; i < 600 && sub_count == 0; ++i)
  {
    pub.publish(m);
    ros::spinOnce();
    client_nh.spinOnce();
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_GT(sub_count, 0);
  EXPECT_EQ(sub_last, m.data);
}

static bool served = false;
static void onEmpty(const rosserial::std_srvs::Empty::Request&, rosserial::std_srvs::Empty::Response&)
{
  served = true;
}

TEST_F(Fixture, single_service_server_and_params)
{
  rosserial::ros::ServiceServer<rosserial::std_srvs::Empty::Request, rosserial::std_srvs::Empty::Response> server(
      "test_srv", &onEmpty);
  client_nh.advertiseService(server);
  client_nh.initNode();
  ros::ServiceClient client = nh.serviceClient<std_srvs::Empty>("test_srv");
  std::thread caller(
      [&]
      {
        std_srvs::Empty srv;
        for (int i = 0; i < 100 && !served; ++i)
        {
          if (client.waitForExistence(ros::Duration(0.2)) && client.call(srv))
            break;
        }
      });
  for (int i = 0; i < 1200 && !served; ++i)
  {
    client_nh.spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  for (int i = 0; i < 100; ++i)  // let the response go out
  {
    client_nh.spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  caller.join();
  EXPECT_TRUE(served);
  int iv = 0;
  float fv = 0;
  bool bv = false;
  char text[20] = "";
  char* tp = text;
  EXPECT_TRUE(client_nh.getParam("int_value", &iv));
  EXPECT_TRUE(client_nh.getParam("float_value", &fv));
  EXPECT_TRUE(client_nh.getParam("bool_value", &bv));
  EXPECT_TRUE(client_nh.getParam("string_value", &tp));
  EXPECT_EQ(iv, 1);
  EXPECT_EQ(fv, 0.5f);
  EXPECT_TRUE(bv);
  EXPECT_STREQ(text, "sample text");
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "test_publish_subscribe");
  ros::start();
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
