// ControllerManager semantics on a DummyRobotHW, in-process (no ROS services called):
// loading errors, strict/best-effort switches, resource conflicts, unload of a running
// controller, start_asap / timeout / hardware switch errors, a stalled loop, reset.
// Run by test/cm_switch.test (a master is needed for parameters). Time is simulated: the
// loop thread advances its own clock by 10 ms per update.
#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <controller_manager/controller_manager.h>
#include <controller_manager_tests/dummy_robot_hw.h>
#include <controller_manager_tests/effort_test_controller.h>
#include <controller_manager_tests/multi_test_controller.h>
#include <controller_manager_tests/state_test_controller.h>
#include <controller_manager_tests/velocity_test_controller.h>

using controller_manager::ControllerManager;
using controller_manager_tests::DummyRobotHW;
using hardware_interface::RobotHW;
typedef controller_manager_msgs::SwitchController::Request Req;

/// Throws from update() (after \p ok_updates updates) or from starting().
class ThrowingController : public controller_interface::Controller<hardware_interface::JointStateInterface>
{
public:
  bool init(hardware_interface::JointStateInterface* /*hw*/, ros::NodeHandle& nh) override
  {
    throw_in_starting_ = nh.param("throw_in_starting", false);
    return true;
  }
  void starting(const ros::Time& /*time*/) override
  {
    if (throw_in_starting_)
      throw std::runtime_error("starting failed on purpose");
  }
  void update(const ros::Time& /*time*/, const ros::Duration& /*period*/) override
  {
    if (++updates_ > 3)
      throw std::runtime_error("update failed on purpose");
  }
  int updates_ = 0;
  bool throw_in_starting_ = false;
};

/// Creates the test controllers in-process (besides the pluginlib loader).
class LocalLoader : public controller_manager::ControllerLoaderInterface
{
public:
  LocalLoader() : ControllerLoaderInterface("local_test_loader") {}
  controller_interface::ControllerBaseSharedPtr createInstance(const std::string& type) override
  {
    if (type == "local/Effort")
      return std::make_shared<controller_manager_tests::EffortTestController>();
    if (type == "local/Velocity")
      return std::make_shared<controller_manager_tests::VelocityTestController>();
    if (type == "local/State")
      return std::make_shared<controller_manager_tests::StateTestController>();
    if (type == "local/Multi")
      return std::make_shared<controller_manager_tests::MultiTestController>();
    if (type == "local/Throwing")
      return std::make_shared<ThrowingController>();
    if (type == "local/Throws")
      throw std::runtime_error("this loader refuses local/Throws");
    return nullptr;
  }
  std::vector<std::string> getDeclaredClasses() override
  {
    return { "local/Effort", "local/Velocity", "local/State", "local/Multi", "local/Throws", "local/Throwing" };
  }
  void reload() override {}
};

class TestCM : public ControllerManager
{
public:
  using ControllerManager::ControllerManager;
  controller_manager_msgs::ListControllers::Response list()
  {
    controller_manager_msgs::ListControllers::Request req;
    controller_manager_msgs::ListControllers::Response resp;
    listControllersSrv(req, resp);
    return resp;
  }
  std::string state(const std::string& name)
  {
    for (const auto& c : list().controller)
      if (c.name == name)
        return c.state;
    return "absent";
  }
};

class CMSwitchTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    ns_ = "cm_switch_" + std::to_string(counter_++);
    nh_ = ros::NodeHandle(ns_);
    hw_ = std::make_unique<DummyRobotHW>(std::vector<std::string>{ "joint1", "joint2", "joint3" });
    cm_ = std::make_unique<TestCM>(hw_.get(), nh_);
    cm_->registerControllerLoader(std::make_shared<LocalLoader>());
    running_ = true;
    loop_ = std::thread(
        [this]()
        {
          ros::Time t(1.0);
          const ros::Duration period(0.01);
          while (running_)
          {
            if (!paused_)
            {
              hw_->read(t, period);
              cm_->update(t, period, reset_next_.exchange(false));
              hw_->write(t, period);
              t += period;
              ++cycles_;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
          }
        });
  }

  void TearDown() override
  {
    running_ = false;
    loop_.join();
    cm_.reset();
    hw_.reset();
    nh_.deleteParam("");
  }

  /// Set `<ns>/<name>/type` (and extra params) and load.
  bool load(const std::string& name, const std::string& type, const std::vector<std::string>& joints = {})
  {
    nh_.setParam(name + "/type", type);
    if (!joints.empty())
      nh_.setParam(name + "/joints", joints);
    return cm_->loadController(name);
  }

  /// Wait (bounded) for \p n more loop cycles.
  void waitCycles(int n)
  {
    const long target = cycles_ + n;
    for (int i = 0; i < 20000 && cycles_ < target; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ASSERT_GE(cycles_, target) << "the update loop did not run " << n << " cycles";
  }

  static int counter_;
  std::string ns_;
  ros::NodeHandle nh_;
  std::unique_ptr<DummyRobotHW> hw_;
  std::unique_ptr<TestCM> cm_;
  std::thread loop_;
  std::atomic<bool> running_{ false }, paused_{ false }, reset_next_{ false };
  std::atomic<long> cycles_{ 0 };
};
int CMSwitchTest::counter_ = 0;

TEST_F(CMSwitchTest, LoadErrors)
{
  EXPECT_FALSE(cm_->loadController("no_type"));  // type not specified
  EXPECT_FALSE(load("unknown", "local/DoesNotExist"));
  EXPECT_FALSE(load("throws", "local/Throws"));
  EXPECT_FALSE(cm_->loadController("bad name!"));  // invalid graph name
  EXPECT_TRUE(load("a", "local/Effort", { "joint1" }));
  EXPECT_FALSE(load("a", "local/Effort", { "joint1" }));  // already loaded
  EXPECT_FALSE(load("missing_joint", "local/Effort", { "nope" }));
  nh_.setParam("failing/fail_init", true);
  EXPECT_FALSE(load("failing", "local/State"));
  EXPECT_EQ("initialized", cm_->state("a"));
  EXPECT_EQ(1u, cm_->list().controller.size());
  EXPECT_NE(nullptr, cm_->getControllerByName("a"));
  EXPECT_EQ(nullptr, cm_->getControllerByName("unknown"));
  EXPECT_FALSE(cm_->unloadController("never_loaded"));
}

TEST_F(CMSwitchTest, PluginlibTypesLoad)
{
  EXPECT_TRUE(load("plugin_effort", "controller_manager_tests/EffortTestController", { "joint2" }));
  EXPECT_FALSE(load("plugin_imu", "controller_manager_tests/ImuTestController"));  // no IMU interface
}

TEST_F(CMSwitchTest, ClaimedResources)
{
  ASSERT_TRUE(load("e", "local/Effort", { "joint1", "joint3" }));
  nh_.setParam("m/velocity_joints", std::vector<std::string>{ "joint2" });
  nh_.setParam("m/position_joints", std::vector<std::string>{ "joint3" });
  ASSERT_TRUE(load("m", "local/Multi"));
  ASSERT_TRUE(load("s", "local/State"));
  auto list = cm_->list();
  ASSERT_EQ(3u, list.controller.size());
  EXPECT_EQ("e", list.controller[0].name);
  EXPECT_EQ("local/Effort", list.controller[0].type);
  ASSERT_EQ(1u, list.controller[0].claimed_resources.size());
  EXPECT_EQ("hardware_interface::EffortJointInterface", list.controller[0].claimed_resources[0].hardware_interface);
  EXPECT_EQ((std::vector<std::string>{ "joint1", "joint3" }), list.controller[0].claimed_resources[0].resources);
  ASSERT_EQ(2u, list.controller[1].claimed_resources.size());
  EXPECT_EQ("hardware_interface::VelocityJointInterface", list.controller[1].claimed_resources[0].hardware_interface);
  EXPECT_EQ(std::vector<std::string>{ "joint2" }, list.controller[1].claimed_resources[0].resources);
  EXPECT_EQ(std::vector<std::string>{ "joint3" }, list.controller[1].claimed_resources[1].resources);
  EXPECT_TRUE(list.controller[2].claimed_resources[0].resources.empty());
  // e and m share joint3: together they conflict
  EXPECT_FALSE(cm_->switchController({ "e", "m" }, {}, Req::STRICT));
  EXPECT_TRUE(cm_->switchController({ "e", "s" }, {}, Req::STRICT));
}

TEST_F(CMSwitchTest, StrictFailsWholeSwitchOnUnknownName)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  EXPECT_FALSE(cm_->switchController({ "a", "nope" }, {}, Req::STRICT));
  waitCycles(3);
  EXPECT_EQ("initialized", cm_->state("a"));
  EXPECT_FALSE(cm_->switchController({ "a" }, { "nope" }, Req::STRICT));
  EXPECT_EQ("initialized", cm_->state("a"));
}

TEST_F(CMSwitchTest, BestEffortSkipsUnknownNames)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  EXPECT_TRUE(cm_->switchController({ "a", "nope" }, { "other" }, Req::BEST_EFFORT));
  EXPECT_EQ("running", cm_->state("a"));
  // strictness 0 = best effort (with a warning)
  EXPECT_TRUE(cm_->switchController({}, { "a", "nope" }, 0));
  EXPECT_EQ("stopped", cm_->state("a"));
}

TEST_F(CMSwitchTest, DoubleStartAndStop)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  EXPECT_FALSE(cm_->switchController({}, { "a" }, Req::STRICT));  // not running
  ASSERT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT));
  EXPECT_FALSE(cm_->switchController({ "a" }, {}, Req::STRICT));  // already running
  EXPECT_TRUE(cm_->switchController({ "a" }, {}, Req::BEST_EFFORT));
  EXPECT_EQ("running", cm_->state("a"));
  // restart in one switch: stop + start
  auto* c = dynamic_cast<controller_manager_tests::EffortTestController*>(cm_->getControllerByName("a"));
  ASSERT_NE(nullptr, c);
  EXPECT_TRUE(cm_->switchController({ "a" }, { "a" }, Req::STRICT));
  EXPECT_EQ(2, c->starts_);
  EXPECT_EQ(1, c->stops_);
}

TEST_F(CMSwitchTest, ControllersRunAndHardwareSwitches)
{
  nh_.setParam("a/effort", 2.5);
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  ASSERT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT));
  EXPECT_EQ(1, hw_->do_switch_calls_);
  waitCycles(3);
  EXPECT_EQ(DummyRobotHW::Mode::EFFORT, hw_->mode(0));
  EXPECT_DOUBLE_EQ(2.5, hw_->command(0));
  EXPECT_EQ(DummyRobotHW::Mode::NONE, hw_->mode(1));
  ASSERT_TRUE(cm_->switchController({}, { "a" }, Req::STRICT));
  EXPECT_EQ(DummyRobotHW::Mode::NONE, hw_->mode(0));
}

TEST_F(CMSwitchTest, ResourceConflictsRefused)
{
  ASSERT_TRUE(load("eff", "local/Effort", { "joint1" }));
  ASSERT_TRUE(load("vel", "local/Velocity", { "joint1", "joint2" }));
  ASSERT_TRUE(load("eff2", "local/Effort", { "joint3" }));
  EXPECT_FALSE(cm_->switchController({ "eff", "vel" }, {}, Req::STRICT));
  EXPECT_FALSE(cm_->switchController({ "eff", "vel" }, {}, Req::BEST_EFFORT));
  EXPECT_EQ("initialized", cm_->state("eff"));
  EXPECT_EQ("initialized", cm_->state("vel"));
  ASSERT_TRUE(cm_->switchController({ "eff" }, {}, Req::STRICT));
  EXPECT_FALSE(cm_->switchController({ "vel" }, {}, Req::STRICT));        // eff still holds joint1
  EXPECT_TRUE(cm_->switchController({ "eff2" }, {}, Req::STRICT));        // disjoint joints
  EXPECT_TRUE(cm_->switchController({ "vel" }, { "eff" }, Req::STRICT));  // hand over joint1
  EXPECT_EQ("stopped", cm_->state("eff"));
  EXPECT_EQ("running", cm_->state("vel"));
  EXPECT_EQ(DummyRobotHW::Mode::VELOCITY, hw_->mode(0));
}

TEST_F(CMSwitchTest, UnloadRunningRefused)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  ASSERT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT));
  EXPECT_FALSE(cm_->unloadController("a"));
  EXPECT_EQ("running", cm_->state("a"));
  ASSERT_TRUE(cm_->switchController({}, { "a" }, Req::STRICT));
  EXPECT_TRUE(cm_->unloadController("a"));
  EXPECT_EQ("absent", cm_->state("a"));
  EXPECT_TRUE(load("a", "local/Velocity", { "joint1" }));  // the name is free again
}

TEST_F(CMSwitchTest, HardwareSwitchTimeoutAborts)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  hw_->switch_result_ = RobotHW::SwitchState::ONGOING;
  // 0.2 s of controller time: the loop aborts the start after ~20 cycles
  EXPECT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT, false, 0.2));
  EXPECT_EQ("aborted", cm_->state("a"));
}

TEST_F(CMSwitchTest, HardwareSwitchErrorAborts)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  hw_->switch_result_ = RobotHW::SwitchState::ERROR;
  EXPECT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT));
  EXPECT_EQ("aborted", cm_->state("a"));
  hw_->switch_result_ = RobotHW::SwitchState::DONE;
  EXPECT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT));  // an aborted controller can start again
  EXPECT_EQ("running", cm_->state("a"));
}

TEST_F(CMSwitchTest, StartAsap)
{
  ASSERT_TRUE(load("fast", "local/Effort", { "joint1" }));
  ASSERT_TRUE(load("slow", "local/Effort", { "joint2" }));
  hw_->switch_result_ = RobotHW::SwitchState::ONGOING;
  hw_->controller_switch_result_["fast"] = RobotHW::SwitchState::DONE;
  EXPECT_TRUE(cm_->switchController({ "fast", "slow" }, {}, Req::STRICT, true, 0.1));
  EXPECT_EQ("running", cm_->state("fast"));
  EXPECT_EQ("aborted", cm_->state("slow"));
}

TEST_F(CMSwitchTest, StalledLoopDoesNotHangTheCaller)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  paused_ = true;
  cm_->setSwitchWaitTimeout(0.5);
  EXPECT_FALSE(cm_->switchController({ "a" }, {}, Req::STRICT));
  paused_ = false;
  waitCycles(5);
  EXPECT_EQ("initialized", cm_->state("a"));  // the withdrawn switch is not performed later
  cm_->setSwitchWaitTimeout(30.0);
  EXPECT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT));
}

TEST_F(CMSwitchTest, UnboundedWaitOutlastsAPausedLoop)
{
  // gazebo_ros_control's setting: a paused world calls no update(); the switch requested
  // meanwhile is carried out once the loop runs again, however long the pause (here 2 s, 4x
  // the bound after which StalledLoopDoesNotHangTheCaller's switch is withdrawn)
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  paused_ = true;
  cm_->setSwitchWaitTimeout(0.0);
  std::atomic<int> result{ -1 };
  std::thread caller([this, &result]() { result = cm_->switchController({ "a" }, {}, Req::STRICT) ? 1 : 0; });
  std::this_thread::sleep_for(std::chrono::milliseconds(2000));
  EXPECT_EQ(-1, result.load());  // still waiting, not withdrawn (state() would wait for it too)
  paused_ = false;
  caller.join();
  cm_->setSwitchWaitTimeout(30.0);
  EXPECT_EQ(1, result.load());
  EXPECT_EQ("running", cm_->state("a"));
}

TEST_F(CMSwitchTest, ResetRestartsRunningControllers)
{
  ASSERT_TRUE(load("a", "local/Effort", { "joint1" }));
  ASSERT_TRUE(load("b", "local/Effort", { "joint2" }));
  ASSERT_TRUE(cm_->switchController({ "a" }, {}, Req::STRICT));
  auto* a = dynamic_cast<controller_manager_tests::EffortTestController*>(cm_->getControllerByName("a"));
  auto* b = dynamic_cast<controller_manager_tests::EffortTestController*>(cm_->getControllerByName("b"));
  reset_next_ = true;
  waitCycles(3);
  EXPECT_EQ(2, a->starts_);
  EXPECT_EQ(1, a->stops_);
  EXPECT_EQ(0, b->starts_);
  EXPECT_EQ("running", cm_->state("a"));
}

TEST_F(CMSwitchTest, ThrowingControllerIsAbortedNotFatal)
{
  ASSERT_TRUE(load("bad", "local/Throwing"));
  ASSERT_TRUE(load("good", "local/Effort", { "joint1" }));
  ASSERT_TRUE(cm_->switchController({ "bad", "good" }, {}, Req::STRICT));
  waitCycles(10);
  EXPECT_EQ("aborted", cm_->state("bad"));
  EXPECT_EQ("running", cm_->state("good"));
  nh_.setParam("bad_start/throw_in_starting", true);
  ASSERT_TRUE(load("bad_start", "local/Throwing"));
  EXPECT_TRUE(cm_->switchController({ "bad_start" }, {}, Req::STRICT));
  EXPECT_EQ("aborted", cm_->state("bad_start"));
  EXPECT_TRUE(cm_->unloadController("bad"));
  EXPECT_TRUE(cm_->unloadController("bad_start"));
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "cm_switch_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int rc = RUN_ALL_TESTS();
  ros::shutdown();
  return rc;
}
