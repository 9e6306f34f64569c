// realtime_tools::RealtimeServerGoalHandle without a ROS master: the realtime requests and the
// preallocated messages (forwarding to a live action server is driven by joint_trajectory_controller's rostests).
#include <gtest/gtest.h>

#include <actionlib/TestAction.h>
#include <realtime_tools/realtime_server_goal_handle.h>

using realtime_tools::RealtimeServerGoalHandle;
typedef RealtimeServerGoalHandle<actionlib::TestAction> RtGoalHandle;

TEST(RealtimeServerGoalHandle, PreallocatesResultAndFeedback)
{
  actionlib::ServerGoalHandle<actionlib::TestAction> gh;
  RtGoalHandle rt(gh);
  ASSERT_TRUE(rt.preallocated_result_ != nullptr);
  ASSERT_TRUE(rt.preallocated_feedback_ != nullptr);
  EXPECT_FALSE(rt.req_abort_);
  EXPECT_FALSE(rt.req_cancel_);
  EXPECT_FALSE(rt.req_succeed_);

  boost::shared_ptr<actionlib::TestResult> result(new actionlib::TestResult);
  boost::shared_ptr<actionlib::TestFeedback> feedback(new actionlib::TestFeedback);
  RtGoalHandle rt2(gh, result, feedback);
  EXPECT_EQ(result.get(), rt2.preallocated_result_.get());
  EXPECT_EQ(feedback.get(), rt2.preallocated_feedback_.get());
}

TEST(RealtimeServerGoalHandle, FirstRequestWins)
{
  actionlib::ServerGoalHandle<actionlib::TestAction> gh;
  RtGoalHandle rt(gh);
  rt.preallocated_result_->result = 7;
  rt.setAborted(rt.preallocated_result_);
  rt.setSucceeded();
  rt.setCanceled();
  EXPECT_TRUE(rt.req_abort_);
  EXPECT_FALSE(rt.req_succeed_);
  EXPECT_FALSE(rt.req_cancel_);
  ASSERT_TRUE(rt.req_result_ != nullptr);
  EXPECT_EQ(7, rt.req_result_->result);

  RtGoalHandle rt_succ(gh);
  rt_succ.setSucceeded();
  rt_succ.setAborted();
  EXPECT_TRUE(rt_succ.req_succeed_);
  EXPECT_FALSE(rt_succ.req_abort_);
  EXPECT_TRUE(rt_succ.req_result_ == nullptr);

  RtGoalHandle rt_cancel(gh);
  rt_cancel.setCanceled();
  rt_cancel.setSucceeded();
  EXPECT_TRUE(rt_cancel.req_cancel_);
  EXPECT_FALSE(rt_cancel.req_succeed_);
}

TEST(RealtimeServerGoalHandle, FeedbackIsReplacedAndInvalidHandleIsLeftAlone)
{
  actionlib::ServerGoalHandle<actionlib::TestAction> gh;
  RtGoalHandle rt(gh);
  EXPECT_FALSE(rt.valid());
  rt.preallocated_feedback_->feedback = 3;
  rt.setFeedback(rt.preallocated_feedback_);
  ASSERT_TRUE(rt.req_feedback_ != nullptr);
  EXPECT_EQ(3, rt.req_feedback_->feedback);
  rt.setSucceeded();
  rt.runNonRealtime(ros::TimerEvent());  // no goal: nothing is forwarded, nothing throws
  EXPECT_TRUE(rt.req_succeed_);
}
