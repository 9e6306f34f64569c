// Test fixture of the controller_manager re-implementation: a RobotHW with simulated joints.
#include <controller_manager_tests/dummy_robot_hw.h>

#include <algorithm>

namespace controller_manager_tests
{
DummyRobotHW::DummyRobotHW(const std::vector<std::string>& joint_names)
  : names_(joint_names)
  , pos_(names_.size(), 0.0)
  , vel_(names_.size(), 0.0)
  , eff_(names_.size(), 0.0)
  , cmd_(names_.size(), 0.0)
  , mode_(names_.size(), Mode::NONE)
{
  for (size_t i = 0; i < names_.size(); ++i)
  {
    hardware_interface::JointStateHandle state(names_[i], &pos_[i], &vel_[i], &eff_[i]);
    jsi_.registerHandle(state);
    eji_.registerHandle(hardware_interface::JointHandle(state, &cmd_[i]));
    vji_.registerHandle(hardware_interface::JointHandle(state, &cmd_[i]));
    pji_.registerHandle(hardware_interface::JointHandle(state, &cmd_[i]));
  }
  registerInterface(&jsi_);
  registerInterface(&eji_);
  registerInterface(&vji_);
  registerInterface(&pji_);
}

void DummyRobotHW::read(const ros::Time& /*time*/, const ros::Duration& /*period*/) {}

void DummyRobotHW::write(const ros::Time& /*time*/, const ros::Duration& period)
{
  const double dt = period.toSec();
  for (size_t i = 0; i < names_.size(); ++i)
  {
    switch (mode_[i])
    {
      case Mode::EFFORT:
        eff_[i] = cmd_[i];
        vel_[i] += cmd_[i] * dt;
        pos_[i] += vel_[i] * dt;
        break;
      case Mode::VELOCITY:
        vel_[i] = cmd_[i];
        pos_[i] += vel_[i] * dt;
        break;
      case Mode::POSITION:
        vel_[i] = dt > 0.0 ? (cmd_[i] - pos_[i]) / dt : 0.0;
        pos_[i] = cmd_[i];
        break;
      case Mode::NONE:
        vel_[i] = 0.0;
        eff_[i] = 0.0;
        break;
    }
  }
}

static DummyRobotHW::Mode modeOf(const std::string& iface)
{
  if (iface == "hardware_interface::EffortJointInterface")
    return DummyRobotHW::Mode::EFFORT;
  if (iface == "hardware_interface::VelocityJointInterface")
    return DummyRobotHW::Mode::VELOCITY;
  if (iface == "hardware_interface::PositionJointInterface")
    return DummyRobotHW::Mode::POSITION;
  return DummyRobotHW::Mode::NONE;
}

void DummyRobotHW::doSwitch(const std::list<hardware_interface::ControllerInfo>& start_list,
                            const std::list<hardware_interface::ControllerInfo>& stop_list)
{
  ++do_switch_calls_;
  auto index = [this](const std::string& name)
  { return static_cast<size_t>(std::find(names_.begin(), names_.end(), name) - names_.begin()); };
  for (const auto& info : stop_list)
    for (const auto& res : info.claimed_resources)
      for (const auto& joint : res.resources)
        if (index(joint) < names_.size() && modeOf(res.hardware_interface) != Mode::NONE)
        {
          mode_[index(joint)] = Mode::NONE;
          cmd_[index(joint)] = 0.0;
        }
  for (const auto& info : start_list)
    for (const auto& res : info.claimed_resources)
      for (const auto& joint : res.resources)
        if (index(joint) < names_.size() && modeOf(res.hardware_interface) != Mode::NONE)
          mode_[index(joint)] = modeOf(res.hardware_interface);
}

hardware_interface::RobotHW::SwitchState DummyRobotHW::switchResult(
    const hardware_interface::ControllerInfo& info) const
{
  auto it = controller_switch_result_.find(info.name);
  return it == controller_switch_result_.end() ? switch_result_ : it->second;
}

}  // namespace controller_manager_tests
