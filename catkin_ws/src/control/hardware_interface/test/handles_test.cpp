// Joint/actuator/IMU handles: data access and null-pointer exceptions with the original texts.
#include <functional>

#include <gtest/gtest.h>

#include <hardware_interface/actuator_command_interface.h>
#include <hardware_interface/force_torque_sensor_interface.h>
#include <hardware_interface/posvel_command_interface.h>
#include <hardware_interface/imu_sensor_interface.h>
#include <hardware_interface/joint_command_interface.h>

using namespace hardware_interface;

static std::string errorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const HardwareInterfaceException& e)
  {
    return e.what();
  }
  return "";
}

TEST(JointStateHandleTest, NullPointersThrowWithName)
{
  double v = 0.0;
  EXPECT_EQ("Cannot create handle 'j'. Position data pointer is null.",
            errorOf([&] { JointStateHandle("j", nullptr, &v, &v); }));
  EXPECT_EQ("Cannot create handle 'j'. Velocity data pointer is null.",
            errorOf([&] { JointStateHandle("j", &v, nullptr, &v); }));
  EXPECT_EQ("Cannot create handle 'j'. Effort data pointer is null.",
            errorOf([&] { JointStateHandle("j", &v, &v, nullptr); }));
  EXPECT_EQ("Cannot create handle 'j'. Absolute encoder position data pointer is null.",
            errorOf([&] { JointStateHandle("j", &v, &v, &v, nullptr); }));
  EXPECT_EQ("Cannot create handle 'j'. Torque sensor data pointer is null.",
            errorOf([&] { JointStateHandle("j", &v, &v, &v, nullptr, true); }));
}

TEST(JointStateHandleTest, Accessors)
{
  double pos = 1.0, vel = 2.0, eff = 3.0, abs_pos = 4.0, torque = 5.0;
  JointStateHandle plain("j", &pos, &vel, &eff);
  EXPECT_EQ("j", plain.getName());
  EXPECT_DOUBLE_EQ(1.0, plain.getPosition());
  EXPECT_DOUBLE_EQ(2.0, plain.getVelocity());
  EXPECT_DOUBLE_EQ(3.0, plain.getEffort());
  EXPECT_EQ(&pos, plain.getPositionPtr());
  EXPECT_FALSE(plain.hasAbsolutePosition());
  EXPECT_FALSE(plain.hasTorqueSensor());
  EXPECT_THROW(plain.getAbsolutePosition(), std::runtime_error);
  EXPECT_THROW(plain.getTorqueSensor(), std::runtime_error);

  JointStateHandle full("j", &pos, &vel, &eff, &abs_pos, &torque);
  EXPECT_DOUBLE_EQ(4.0, full.getAbsolutePosition());
  EXPECT_DOUBLE_EQ(5.0, full.getTorqueSensor());

  JointStateHandle torque_only("j", &pos, &vel, &eff, &torque, true);
  EXPECT_FALSE(torque_only.hasAbsolutePosition());
  EXPECT_DOUBLE_EQ(5.0, torque_only.getTorqueSensor());
}

TEST(JointHandleTest, CommandPointer)
{
  double pos = 1.0, vel = 2.0, eff = 3.0, cmd = 0.0;
  JointStateHandle js("j", &pos, &vel, &eff);
  EXPECT_EQ("Cannot create handle 'j'. Command data pointer is null.", errorOf([&] { JointHandle(js, nullptr); }));
  JointHandle h(js, &cmd);
  h.setCommand(9.0);
  EXPECT_DOUBLE_EQ(9.0, cmd);
  EXPECT_DOUBLE_EQ(9.0, h.getCommand());
  EXPECT_DOUBLE_EQ(1.0, h.getPosition());
}

TEST(ActuatorHandleTest, CommandAndNulls)
{
  double pos = 1.0, vel = 2.0, eff = 3.0, cmd = 0.0;
  EXPECT_EQ("Cannot create handle 'a'. Position data pointer is null.",
            errorOf([&] { ActuatorStateHandle("a", nullptr, &vel, &eff); }));
  ActuatorStateHandle as("a", &pos, &vel, &eff);
  EXPECT_EQ("Cannot create handle 'a'. Command data pointer is null.", errorOf([&] { ActuatorHandle(as, nullptr); }));
  VelocityActuatorInterface iface;
  iface.registerHandle(ActuatorHandle(as, &cmd));
  iface.getHandle("a").setCommand(0.5);
  EXPECT_DOUBLE_EQ(0.5, cmd);
  EXPECT_TRUE(iface.getClaims().empty());  // actuator interfaces do not claim (as the original)
}

TEST(ImuSensorHandleTest, Data)
{
  double orientation[4] = { 0, 0, 0, 1 };
  double gyro[3] = { 0.1, 0.2, 0.3 };
  ImuSensorHandle::Data data;
  data.name = "imu";
  data.frame_id = "imu_link";
  data.orientation = orientation;
  data.angular_velocity = gyro;
  ImuSensorHandle h(data);
  EXPECT_EQ("imu", h.getName());
  EXPECT_EQ("imu_link", h.getFrameId());
  EXPECT_DOUBLE_EQ(1.0, h.getOrientation()[3]);
  EXPECT_DOUBLE_EQ(0.2, h.getAngularVelocity()[1]);
  EXPECT_EQ(nullptr, h.getLinearAcceleration());
  ImuSensorInterface iface;
  iface.registerHandle(h);
  EXPECT_EQ("imu_link", iface.getHandle("imu").getFrameId());
}

TEST(PosVelJointHandleTest, Commands)
{
  double pos = 1.0, vel = 2.0, eff = 3.0, cp = 0.0, cv = 0.0;
  JointStateHandle js("j", &pos, &vel, &eff);
  EXPECT_EQ("Cannot create handle 'j'. Command position pointer is null.",
            errorOf([&] { PosVelJointHandle(js, nullptr, &cv); }));
  PosVelJointInterface iface;
  iface.registerHandle(PosVelJointHandle(js, &cp, &cv));
  iface.getHandle("j").setCommand(0.5, -0.5);
  EXPECT_DOUBLE_EQ(0.5, cp);
  EXPECT_DOUBLE_EQ(-0.5, cv);
  EXPECT_EQ(1u, iface.getClaims().size());
}

TEST(ForceTorqueSensorHandleTest, Data)
{
  double force[3] = { 1, 2, 3 }, torque[3] = { 4, 5, 6 };
  ForceTorqueSensorInterface iface;
  iface.registerHandle(ForceTorqueSensorHandle("ft", "ft_link", force, torque));
  EXPECT_DOUBLE_EQ(5.0, iface.getHandle("ft").getTorque()[1]);
  EXPECT_EQ("ft_link", iface.getHandle("ft").getFrameId());
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
