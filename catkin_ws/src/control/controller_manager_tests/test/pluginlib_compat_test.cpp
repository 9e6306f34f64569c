// The ROS 1 pluginlib header names of pluginlib_compat: pluginlib::ClassLoader (from
// <pluginlib/class_loader.h>) finds and instantiates a controller exported with
// <pluginlib/class_list_macros.h>. No master needed (catkin plugin discovery uses rospack).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <pluginlib/class_loader.h>

#include <controller_interface/controller_base.h>

namespace
{
const char* const COMPAT_TYPE = "controller_manager_tests/CompatTestController";
}

TEST(PluginlibCompatTest, ClassLoaderFindsAndCreatesCompatController)
{
  pluginlib::ClassLoader<controller_interface::ControllerBase> loader("controller_interface",
                                                                      "controller_interface::ControllerBase");
  const std::vector<std::string> classes = loader.getDeclaredClasses();
  ASSERT_NE(classes.end(), std::find(classes.begin(), classes.end(), COMPAT_TYPE))
      << "CompatTestController is not declared: is the workspace sourced (scripts/env.sh)?";
  ASSERT_TRUE(loader.isClassAvailable(COMPAT_TYPE));
  std::shared_ptr<controller_interface::ControllerBase> controller;
  ASSERT_NO_THROW(controller = loader.createSharedInstance(COMPAT_TYPE));
  ASSERT_TRUE(controller != nullptr);
  EXPECT_FALSE(controller->isInitialized());  // constructed only
  EXPECT_FALSE(controller->isRunning());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
