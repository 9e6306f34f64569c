// rostest node: RealtimePublisher delivers what the realtime side hands over, in order, and
// trylock() succeeds while fewer than queue_size handed-over messages wait to be published.
#include <gtest/gtest.h>

#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include <realtime_tools/realtime_publisher.h>

/// A subscriber of ~topic collecting what arrives (connected() waits for its publisher).
struct Receiver
{
  std::vector<double> received;
  std::mutex mutex;
  ros::Subscriber sub;

  Receiver(ros::NodeHandle& nh, const std::string& topic)
  {
    sub = nh.subscribe<std_msgs::Float64>(topic, 100,
                                          [this](const std_msgs::Float64::ConstPtr& msg)
                                          {
                                            std::lock_guard<std::mutex> guard(mutex);
                                            received.push_back(msg->data);
                                          });
  }

  bool connected()
  {
    for (int i = 0; i < 3000 && sub.getNumPublishers() == 0; ++i)
      ros::WallDuration(0.01).sleep();
    return sub.getNumPublishers() == 1u;
  }

  /// Waits (up to 30 s) for n messages; returns what arrived.
  std::vector<double> await(std::size_t n)
  {
    for (int i = 0; i < 3000; ++i)
    {
      {
        std::lock_guard<std::mutex> guard(mutex);
        if (received.size() >= n)
          break;
      }
      ros::WallDuration(0.01).sleep();
    }
    std::lock_guard<std::mutex> guard(mutex);
    return received;
  }
};

TEST(RealtimePublisher, PublishesHandedOverMessages)
{
  ros::NodeHandle nh("~");
  Receiver receiver(nh, "out");
  realtime_tools::RealtimePublisher<std_msgs::Float64> pub(nh, "out", 10);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ASSERT_TRUE(receiver.connected()) << "subscriber never connected to the realtime publisher";

  for (int value = 1; value <= 5; ++value)
  {
    // wait until the publishing thread takes hand-overs again
    int tries = 0;
    while (!pub.trylock())
    {
      ASSERT_LT(++tries, 100000) << "trylock() never succeeded again";
      ros::WallDuration(0.0001).sleep();
    }
    pub.msg_.data = value;
    pub.unlockAndPublish();
  }
  const std::vector<double> received = receiver.await(5);
  ASSERT_EQ(5u, received.size()) << "not every handed-over message arrived";
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(i + 1.0, received[i]);
  EXPECT_TRUE(pub.is_running());
}

TEST(RealtimePublisher, QueueSizeMessagesMayWaitForThePublishingThread)
{
  ros::NodeHandle nh("~");
  Receiver receiver(nh, "burst");
  realtime_tools::RealtimePublisher<std_msgs::Float64> pub(nh, "burst", 20);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ASSERT_TRUE(receiver.connected()) << "subscriber never connected to the realtime publisher";

  // a burst of 20 hand-overs, none waiting for the thread: each trylock() succeeds, however far
  // the publishing thread has got
  for (int value = 1; value <= 20; ++value)
  {
    ASSERT_TRUE(pub.trylock()) << "trylock() refused hand-over " << value << " of a queue of 20";
    pub.msg_.data = value;
    pub.unlockAndPublish();
  }
  const std::vector<double> received = receiver.await(20);
  ASSERT_EQ(20u, received.size()) << "not every handed-over message arrived";
  for (int i = 0; i < 20; ++i)
    EXPECT_EQ(i + 1.0, received[i]);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "realtime_publisher_test");
  return RUN_ALL_TESTS();
}
