// Test fixture of the controller_manager re-implementation: a RobotHW with simulated joints.
#pragma once

#include <list>
#include <map>
#include <string>
#include <vector>

#include <hardware_interface/controller_info.h>
#include <hardware_interface/joint_command_interface.h>
#include <hardware_interface/joint_state_interface.h>
#include <hardware_interface/robot_hw.h>

namespace controller_manager_tests
{
/**
 * \brief Joints that integrate their commands: every joint is registered in the joint state,
 * effort, velocity and position interfaces; doSwitch() selects per joint which command is
 * applied (that of the interface the started controller claimed it through).
 *
 * Effort: unit inertia (acceleration = effort); velocity: followed exactly; position: set.
 * switchResult() can be scripted to test start_asap / timeouts.
 */
class DummyRobotHW : public hardware_interface::RobotHW
{
public:
  enum class Mode
  {
    NONE,
    EFFORT,
    VELOCITY,
    POSITION
  };

  explicit DummyRobotHW(const std::vector<std::string>& joint_names);

  void read(const ros::Time& time, const ros::Duration& period) override;
  void write(const ros::Time& time, const ros::Duration& period) override;
  void doSwitch(const std::list<hardware_interface::ControllerInfo>& start_list,
                const std::list<hardware_interface::ControllerInfo>& stop_list) override;
  SwitchState switchResult() const override { return switch_result_; }
  SwitchState switchResult(const hardware_interface::ControllerInfo& info) const override;

  const std::vector<std::string>& jointNames() const { return names_; }
  double position(size_t i) const { return pos_[i]; }
  double velocity(size_t i) const { return vel_[i]; }
  double command(size_t i) const { return cmd_[i]; }
  Mode mode(size_t i) const { return mode_[i]; }

  /// Scripted switch results (default DONE); per controller overrides for switchResult(info).
  SwitchState switch_result_ = SwitchState::DONE;
  std::map<std::string, SwitchState> controller_switch_result_;
  int do_switch_calls_ = 0;

private:
  std::vector<std::string> names_;
  std::vector<double> pos_, vel_, eff_, cmd_;
  std::vector<Mode> mode_;
  hardware_interface::JointStateInterface jsi_;
  hardware_interface::EffortJointInterface eji_;
  hardware_interface::VelocityJointInterface vji_;
  hardware_interface::PositionJointInterface pji_;
};

}  // namespace controller_manager_tests
