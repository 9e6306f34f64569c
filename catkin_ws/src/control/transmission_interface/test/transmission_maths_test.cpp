// SimpleTransmission and DifferentialTransmission maths: known values and round trips.
#include <gtest/gtest.h>

#include <transmission_interface/differential_transmission.h>
#include <transmission_interface/simple_transmission.h>

using namespace transmission_interface;

static const double EPS = 1e-12;

TEST(SimpleTransmissionTest, ZeroReductionRefused)
{
  EXPECT_THROW(SimpleTransmission(0.0), TransmissionInterfaceException);
}

TEST(SimpleTransmissionTest, ActuatorToJoint)
{
  SimpleTransmission t(10.0, 1.0);
  double a_pos = 20.0, a_vel = 5.0, a_eff = 2.0, j_pos = 0, j_vel = 0, j_eff = 0;
  ActuatorData a;
  a.position = { &a_pos };
  a.velocity = { &a_vel };
  a.effort = { &a_eff };
  JointData j;
  j.position = { &j_pos };
  j.velocity = { &j_vel };
  j.effort = { &j_eff };
  t.actuatorToJointPosition(a, j);
  t.actuatorToJointVelocity(a, j);
  t.actuatorToJointEffort(a, j);
  EXPECT_NEAR(3.0, j_pos, EPS);   // 20 / 10 + 1
  EXPECT_NEAR(0.5, j_vel, EPS);   // 5 / 10
  EXPECT_NEAR(20.0, j_eff, EPS);  // 2 * 10

  double b_pos = 0, b_vel = 0, b_eff = 0;
  ActuatorData b;
  b.position = { &b_pos };
  b.velocity = { &b_vel };
  b.effort = { &b_eff };
  t.jointToActuatorPosition(j, b);
  t.jointToActuatorVelocity(j, b);
  t.jointToActuatorEffort(j, b);
  EXPECT_NEAR(a_pos, b_pos, EPS);
  EXPECT_NEAR(a_vel, b_vel, EPS);
  EXPECT_NEAR(a_eff, b_eff, EPS);
  EXPECT_EQ(1u, t.numActuators());
  EXPECT_DOUBLE_EQ(1.0, t.getJointOffset());
}

TEST(SimpleTransmissionTest, NegativeReductionFlipsDirection)
{
  SimpleTransmission t(-2.0);
  double a = 4.0, j = 0.0;
  ActuatorData ad;
  ad.velocity = { &a };
  JointData jd;
  jd.velocity = { &j };
  t.actuatorToJointVelocity(ad, jd);
  EXPECT_NEAR(-2.0, j, EPS);
}

TEST(SimpleTransmissionTest, WrongSizesThrow)
{
  SimpleTransmission t(1.0);
  ActuatorData a;
  JointData j;
  EXPECT_THROW(t.actuatorToJointEffort(a, j), TransmissionInterfaceException);
}

TEST(DifferentialTransmissionTest, RoundTrip)
{
  DifferentialTransmission t({ 10.0, 20.0 }, { 2.0, 3.0 }, { 0.1, -0.2 });
  double ap[2] = { 1.0, -3.0 }, av[2] = { 2.0, 4.0 }, ae[2] = { 0.5, 0.25 };
  double jp[2] = { 0, 0 }, jv[2] = { 0, 0 }, je[2] = { 0, 0 };
  ActuatorData a;
  a.position = { &ap[0], &ap[1] };
  a.velocity = { &av[0], &av[1] };
  a.effort = { &ae[0], &ae[1] };
  JointData j;
  j.position = { &jp[0], &jp[1] };
  j.velocity = { &jv[0], &jv[1] };
  j.effort = { &je[0], &je[1] };
  t.actuatorToJointPosition(a, j);
  t.actuatorToJointVelocity(a, j);
  t.actuatorToJointEffort(a, j);
  EXPECT_NEAR((2.0 / 10 + 4.0 / 20) / (2 * 2.0), jv[0], EPS);
  EXPECT_NEAR((2.0 / 10 - 4.0 / 20) / (2 * 3.0), jv[1], EPS);
  EXPECT_NEAR(2.0 * (0.5 * 10 + 0.25 * 20), je[0], EPS);
  EXPECT_NEAR((1.0 / 10 - 3.0 / 20) / (2 * 2.0) + 0.1, jp[0], EPS);

  double bp[2], bv[2], be[2];
  ActuatorData b;
  b.position = { &bp[0], &bp[1] };
  b.velocity = { &bv[0], &bv[1] };
  b.effort = { &be[0], &be[1] };
  t.jointToActuatorPosition(j, b);
  t.jointToActuatorVelocity(j, b);
  t.jointToActuatorEffort(j, b);
  for (int i = 0; i < 2; ++i)
  {
    EXPECT_NEAR(ap[i], bp[i], 1e-9);
    EXPECT_NEAR(av[i], bv[i], 1e-9);
    EXPECT_NEAR(ae[i], be[i], 1e-9);
  }
}

TEST(DifferentialTransmissionTest, BadParameters)
{
  EXPECT_THROW(DifferentialTransmission({ 1.0 }, { 1.0, 1.0 }), TransmissionInterfaceException);
  EXPECT_THROW(DifferentialTransmission({ 1.0, 0.0 }, { 1.0, 1.0 }), TransmissionInterfaceException);
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
