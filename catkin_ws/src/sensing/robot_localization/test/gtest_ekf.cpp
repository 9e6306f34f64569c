// The EKF core without ROS: constant-velocity prediction along a turned heading, a fused
// measurement pulling the state, the Mahalanobis gate, angle wrapping and NaN detection.
#include <gtest/gtest.h>

#include <cmath>

#include "robot_localization/ekf.h"

using namespace robot_localization;

namespace
{
Eigen::VectorXi idx(std::initializer_list<int> l) { return Eigen::Map<const Eigen::VectorXi>(l.begin(), l.size()); }
Eigen::VectorXd vec(std::initializer_list<double> l) { return Eigen::Map<const Eigen::VectorXd>(l.begin(), l.size()); }
}  // namespace

TEST(Ekf, PredictsAlongTheHeading)
{
  Ekf ekf;
  ASSERT_TRUE(
      ekf.process(0.0, vec({ 1.0, 0.5 }), Eigen::Matrix2d::Identity() * 1e-6, idx({ StateMemberVx, StateMemberVyaw })));
  ekf.predict(1.0);
  EXPECT_NEAR(ekf.state()(StateMemberX), 1.0, 1e-9);
  EXPECT_NEAR(ekf.state()(StateMemberYaw), 0.5, 1e-9);
  ekf.predict(2.0);
  EXPECT_NEAR(ekf.state()(StateMemberX), 1.0 + std::cos(0.5), 1e-9);
  EXPECT_NEAR(ekf.state()(StateMemberY), std::sin(0.5), 1e-9);
  EXPECT_GT(ekf.covariance()(StateMemberX, StateMemberX), 1e-3);  // process noise grew it
}

TEST(Ekf, CorrectionPullsTowardsTheMeasurementAndTheGateRejects)
{
  Ekf ekf;
  ekf.process(0.0, vec({ 0.0 }), Eigen::Matrix<double, 1, 1>::Constant(1.0), idx({ StateMemberX }));
  ekf.process(0.1, vec({ 1.0 }), Eigen::Matrix<double, 1, 1>::Constant(1.0), idx({ StateMemberX }));
  const double x = ekf.state()(StateMemberX);
  EXPECT_GT(x, 0.3);
  EXPECT_LT(x, 0.7);
  // 100 standard deviations away with a gate of 3: rejected, state unchanged
  EXPECT_FALSE(
      ekf.process(0.2, vec({ 100.0 }), Eigen::Matrix<double, 1, 1>::Constant(0.01), idx({ StateMemberX }), 3.0));
  EXPECT_EQ(ekf.rejected, 1);
  EXPECT_NEAR(ekf.state()(StateMemberX), x, 0.05);
}

TEST(Ekf, BatchEqualsSequentialForADiagonalCovariance)
{
  Ekf a, b;
  for (Ekf* e : { &a, &b })
    e->process(0.0, vec({ 0.0, 0.0, 0.0 }), Eigen::Matrix3d::Identity() * 0.5,
               idx({ StateMemberX, StateMemberY, StateMemberYaw }));
  Eigen::Matrix3d diag = Eigen::Vector3d(0.2, 0.3, 0.1).asDiagonal();
  Eigen::Matrix3d almost = diag;
  almost(0, 1) = almost(1, 0) = 1e-12;  // not diagonal: the batch path
  a.process(0.5, vec({ 1.0, -1.0, 0.3 }), diag, idx({ StateMemberX, StateMemberY, StateMemberYaw }));
  b.process(0.5, vec({ 1.0, -1.0, 0.3 }), almost, idx({ StateMemberX, StateMemberY, StateMemberYaw }));
  EXPECT_LT((a.state() - b.state()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((a.covariance() - b.covariance()).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(Ekf, AnglesWrapAndNanIsDetected)
{
  EXPECT_NEAR(normalizeAngle(3.0 * M_PI / 2.0), -M_PI / 2.0, 1e-12);
  EXPECT_NEAR(normalizeAngle(-7.0), -7.0 + 2.0 * M_PI, 1e-12);
  Ekf ekf;
  ekf.process(0.0, vec({ 3.1 }), Eigen::Matrix<double, 1, 1>::Constant(0.01), idx({ StateMemberYaw }));
  ekf.process(0.1, vec({ -3.1 }), Eigen::Matrix<double, 1, 1>::Constant(0.01), idx({ StateMemberYaw }));
  EXPECT_GT(std::fabs(ekf.state()(StateMemberYaw)), 3.0);  // through +-pi, not through 0
  const Eigen::VectorXd before = ekf.state();
  EXPECT_FALSE(
      ekf.process(0.2, vec({ std::nan("") }), Eigen::Matrix<double, 1, 1>::Constant(0.01), idx({ StateMemberX })));
  EXPECT_TRUE(ekf.nanDetected);
  EXPECT_LT((ekf.state() - before).cwiseAbs().maxCoeff(), 1e-6);  // only predicted to t = 0.2
  EXPECT_TRUE(ekf.state().allFinite());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
