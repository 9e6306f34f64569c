// TransmissionParser: good URDF, missing hardware interfaces, bad documents; loadTransmission types.
#include <gtest/gtest.h>

#include <transmission_interface/simple_transmission.h>
#include <transmission_interface/transmission_loader.h>
#include <transmission_interface/transmission_parser.h>

using namespace transmission_interface;

static const char* const GOOD = R"(<?xml version="1.0"?>
<robot name="diffbot">
  <link name="base_link"/>
  <transmission name="left_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="left_wheel_joint">
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
      <hardwareInterface>hardware_interface/JointStateInterface</hardwareInterface>
    </joint>
    <actuator name="left_motor">
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
      <mechanicalReduction>30</mechanicalReduction>
    </actuator>
  </transmission>
  <transmission name="right_trans">
    <type> transmission_interface/SimpleTransmission </type>
    <joint name="right_wheel_joint">
      <role>joint1</role>
      <offset>0.5</offset>
      <hardwareInterface>EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="right_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>)";

TEST(TransmissionParserTest, GoodUrdf)
{
  std::vector<TransmissionInfo> infos;
  ASSERT_TRUE(TransmissionParser::parse(GOOD, infos));
  ASSERT_EQ(2u, infos.size());
  const TransmissionInfo& left = infos[0];
  EXPECT_EQ("left_trans", left.name);
  EXPECT_EQ("transmission_interface/SimpleTransmission", left.type);
  ASSERT_EQ(1u, left.joints.size());
  EXPECT_EQ("left_wheel_joint", left.joints[0].name);
  EXPECT_EQ((std::vector<std::string>{ "hardware_interface/VelocityJointInterface",
                                       "hardware_interface/JointStateInterface" }),
            left.joints[0].hardware_interfaces);
  EXPECT_TRUE(left.joints[0].role.empty());
  EXPECT_NE(std::string::npos, left.joints[0].xml_element.find("<joint name=\"left_wheel_joint\">"));
  ASSERT_EQ(1u, left.actuators.size());
  EXPECT_EQ("left_motor", left.actuators[0].name);
  EXPECT_TRUE(left.actuators[0].has_mechanical_reduction);
  EXPECT_DOUBLE_EQ(30.0, left.actuators[0].mechanical_reduction);
  EXPECT_NE(std::string::npos, left.actuators[0].xml_element.find("mechanicalReduction"));

  const TransmissionInfo& right = infos[1];
  EXPECT_EQ("transmission_interface/SimpleTransmission", right.type);  // trimmed
  EXPECT_EQ("joint1", right.joints[0].role);
  EXPECT_DOUBLE_EQ(0.5, right.joints[0].offset);
  EXPECT_EQ(std::vector<std::string>{ "EffortJointInterface" }, right.joints[0].hardware_interfaces);
  EXPECT_TRUE(right.actuators[0].hardware_interfaces.empty());
}

TEST(TransmissionParserTest, InvalidTransmissionsAreSkipped)
{
  const char* urdf = R"(<robot name="r">
  <transmission name="no_hw_iface">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"/>
    <actuator name="m1"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
  <transmission>
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j2"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m2"/>
  </transmission>
  <transmission name="no_type">
    <joint name="j3"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m3"/>
  </transmission>
  <transmission name="no_actuator">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j4"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
  </transmission>
  <transmission name="bad_offset">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j5"><offset>abc</offset><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m5"/>
  </transmission>
  <transmission name="ok">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j6"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
    <actuator name="m6"/>
  </transmission>
</robot>)";
  std::vector<TransmissionInfo> infos;
  ASSERT_TRUE(TransmissionParser::parse(urdf, infos));
  ASSERT_EQ(1u, infos.size());
  EXPECT_EQ("ok", infos[0].name);
  EXPECT_FALSE(infos[0].actuators[0].has_mechanical_reduction);
}

TEST(TransmissionParserTest, BadDocuments)
{
  std::vector<TransmissionInfo> infos;
  EXPECT_FALSE(TransmissionParser::parse("", infos));
  EXPECT_FALSE(TransmissionParser::parse("<robot><transmission>", infos));
  EXPECT_FALSE(TransmissionParser::parse("<sdf/>", infos));
  EXPECT_TRUE(TransmissionParser::parse("<robot name='empty'/>", infos));
  EXPECT_TRUE(infos.empty());
}

static TransmissionInfo info(const std::string& type, size_t n, bool reduction = true)
{
  TransmissionInfo t;
  t.name = "t";
  t.type = type;
  for (size_t i = 0; i < n; ++i)
  {
    JointInfo j;
    j.name = "j" + std::to_string(i);
    j.hardware_interfaces.push_back("hardware_interface/EffortJointInterface");
    t.joints.push_back(j);
    ActuatorInfo a;
    a.name = "a" + std::to_string(i);
    a.has_mechanical_reduction = reduction;
    a.mechanical_reduction = 10.0;
    t.actuators.push_back(a);
  }
  return t;
}

TEST(TransmissionLoaderTest, Types)
{
  std::string error;
  TransmissionSharedPtr simple = loadTransmission(info("transmission_interface/SimpleTransmission", 1), error);
  ASSERT_TRUE(simple) << error;
  EXPECT_DOUBLE_EQ(10.0, std::dynamic_pointer_cast<SimpleTransmission>(simple)->getActuatorReduction());

  EXPECT_FALSE(loadTransmission(info("transmission_interface/SimpleTransmission", 1, false), error));
  EXPECT_EQ(
      "Transmission 't' of type 'transmission_interface/SimpleTransmission': actuator 'a0' has no "
      "<mechanicalReduction>.",
      error);
  EXPECT_FALSE(loadTransmission(info("transmission_interface/SimpleTransmission", 2), error));
  EXPECT_NE(std::string::npos, error.find("exactly one joint and one actuator"));

  TransmissionSharedPtr diff = loadTransmission(info("transmission_interface/DifferentialTransmission", 2), error);
  ASSERT_TRUE(diff) << error;
  EXPECT_EQ(2u, diff->numJoints());

  EXPECT_FALSE(loadTransmission(info("transmission_interface/FourBarLinkageTransmission", 2), error));
  EXPECT_NE(std::string::npos, error.find("FourBarLinkageTransmission is not implemented"));
  EXPECT_FALSE(loadTransmission(info("my_pkg/MagicTransmission", 1), error));
  EXPECT_NE(std::string::npos, error.find("unknown transmission type"));

  TransmissionInfo zero = info("transmission_interface/SimpleTransmission", 1);
  zero.actuators[0].mechanical_reduction = 0.0;
  EXPECT_FALSE(loadTransmission(zero, error));
  EXPECT_NE(std::string::npos, error.find("Transmission reduction ratio cannot be zero."));
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
