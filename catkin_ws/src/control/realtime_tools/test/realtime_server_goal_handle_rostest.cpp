// rostest node: RealtimeServerGoalHandle forwards the realtime side's requests to a live
// actionlib server only from runNonRealtime(), and only in the goal states the original allows.
#include <functional>
#include <mutex>
#include <vector>

#include <gtest/gtest.h>

#include <actionlib/TestAction.h>
#include <actionlib/client/simple_action_client.h>
#include <actionlib/server/action_server.h>
#include <boost/make_shared.hpp>
#include <ros/ros.h>

#include <realtime_tools/realtime_server_goal_handle.h>

typedef actionlib::ActionServer<actionlib::TestAction> Server;
typedef realtime_tools::RealtimeServerGoalHandle<actionlib::TestAction> RtGoalHandle;
typedef actionlib::SimpleActionClient<actionlib::TestAction> Client;

class RtGoalHandleTest : public ::testing::Test
{
protected:
  RtGoalHandleTest() : nh_("~"), server_(nh_, "action", false), client_(nh_, "action", false), spinner_(2)
  {
    server_.registerGoalCallback(
        [this](Server::GoalHandle gh)
        {
          gh.setAccepted();
          std::lock_guard<std::mutex> lock(mutex_);
          goals_.push_back(gh);
        });
    server_.registerCancelCallback([](Server::GoalHandle) {});
    server_.start();
    spinner_.start();
  }

  /// Hang guard only: conditions are met as soon as messages arrive.
  static bool waitFor(const std::function<bool()>& cond, double timeout_s = 60.0)
  {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
    while (!cond())
    {
      if (ros::WallTime::now() > deadline)
        return false;
      ros::WallDuration(0.005).sleep();
    }
    return true;
  }

  Server::GoalHandle sendGoal(int value)
  {
    actionlib::TestGoal goal;
    goal.goal = value;
    std::size_t before;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      before = goals_.size();
    }
    client_.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                     [this](const actionlib::TestFeedbackConstPtr& fb)
                     {
                       std::lock_guard<std::mutex> lock(mutex_);
                       feedback_.push_back(fb->feedback);
                     });
    EXPECT_TRUE(waitFor(
        [&]
        {
          std::lock_guard<std::mutex> lock(mutex_);
          return goals_.size() > before;
        }));
    EXPECT_TRUE(waitFor([&] { return client_.getState() == actionlib::SimpleClientGoalState::ACTIVE; }));
    std::lock_guard<std::mutex> lock(mutex_);
    return goals_.back();
  }

  ros::NodeHandle nh_;
  Server server_;
  Client client_;
  ros::AsyncSpinner spinner_;
  std::mutex mutex_;
  std::vector<Server::GoalHandle> goals_;
  std::vector<int> feedback_;
};

TEST_F(RtGoalHandleTest, SucceedWithFeedbackAndResult)
{
  ASSERT_TRUE(client_.waitForServer(ros::Duration(60.0)));
  Server::GoalHandle gh = sendGoal(1);
  auto rt = boost::make_shared<RtGoalHandle>(gh);
  ASSERT_TRUE(rt->valid());

  rt->preallocated_feedback_->feedback = 42;
  rt->setFeedback(rt->preallocated_feedback_);
  rt->preallocated_result_->result = 7;
  rt->setSucceeded(rt->preallocated_result_);
  rt->setFeedback();  // no feedback pending any more
  // Nothing reaches actionlib before the non-realtime side runs.
  ros::WallDuration(0.2).sleep();
  EXPECT_EQ(actionlib::SimpleClientGoalState::ACTIVE, client_.getState().state_);
  rt->req_succeed_ = false;  // (public as in our API) hold the outcome back to see the feedback alone
  rt->setFeedback(rt->preallocated_feedback_);
  rt->runNonRealtime(ros::TimerEvent());
  EXPECT_TRUE(waitFor(
      [&]
      {
        std::lock_guard<std::mutex> lock(mutex_);
        return !feedback_.empty();
      }));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ASSERT_EQ(1u, feedback_.size());
    EXPECT_EQ(42, feedback_[0]);
  }
  EXPECT_EQ(actionlib::SimpleClientGoalState::ACTIVE, client_.getState().state_);

  rt->setFeedback();
  rt->setSucceeded(rt->preallocated_result_);
  rt->runNonRealtime(ros::TimerEvent());
  ASSERT_TRUE(client_.waitForResult(ros::Duration(60.0)));
  EXPECT_EQ(actionlib::SimpleClientGoalState::SUCCEEDED, client_.getState().state_);
  EXPECT_EQ(7, client_.getResult()->result);
}

TEST_F(RtGoalHandleTest, CancelOnlyOncePreempting)
{
  ASSERT_TRUE(client_.waitForServer(ros::Duration(60.0)));
  Server::GoalHandle gh = sendGoal(2);
  RtGoalHandle rt(gh);
  rt.setCanceled();
  rt.runNonRealtime(ros::TimerEvent());  // ACTIVE: a cancel request is not honoured yet
  EXPECT_EQ(actionlib_msgs::GoalStatus::ACTIVE, gh.getGoalStatus().status);

  client_.cancelGoal();
  ASSERT_TRUE(waitFor([&] { return gh.getGoalStatus().status == actionlib_msgs::GoalStatus::PREEMPTING; }));
  rt.runNonRealtime(ros::TimerEvent());
  ASSERT_TRUE(client_.waitForResult(ros::Duration(60.0)));
  EXPECT_EQ(actionlib::SimpleClientGoalState::PREEMPTED, client_.getState().state_);
}

TEST_F(RtGoalHandleTest, AbortWinsOverLaterRequests)
{
  ASSERT_TRUE(client_.waitForServer(ros::Duration(60.0)));
  Server::GoalHandle gh = sendGoal(3);
  RtGoalHandle rt(gh);
  rt.preallocated_result_->result = -1;
  rt.setAborted(rt.preallocated_result_);
  rt.setSucceeded();
  rt.runNonRealtime(ros::TimerEvent());
  ASSERT_TRUE(client_.waitForResult(ros::Duration(60.0)));
  EXPECT_EQ(actionlib::SimpleClientGoalState::ABORTED, client_.getState().state_);
  EXPECT_EQ(-1, client_.getResult()->result);
  rt.runNonRealtime(ros::TimerEvent());  // a finished goal is left alone
  EXPECT_EQ(actionlib_msgs::GoalStatus::ABORTED, gh.getGoalStatus().status);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "realtime_server_goal_handle_test");
  return RUN_ALL_TESTS();
}
