// robot_localization's EKF core (our re-implementation): 15-D state, omnidirectional
// constant-acceleration model, Joseph-form correction with a Mahalanobis gate. No ROS.
// State order: x y z roll pitch yaw (world frame), vx vy vz vroll vpitch vyaw (body frame),
// ax ay az (body frame). Units: m, rad, s.
#ifndef ROBOT_LOCALIZATION_EKF_H
#define ROBOT_LOCALIZATION_EKF_H

#include <Eigen/Dense>
#include <limits>
#include <utility>

namespace robot_localization
{
constexpr int STATE_SIZE = 15;
enum StateMembers
{
  StateMemberX = 0,
  StateMemberY,
  StateMemberZ,
  StateMemberRoll,
  StateMemberPitch,
  StateMemberYaw,
  StateMemberVx,
  StateMemberVy,
  StateMemberVz,
  StateMemberVroll,
  StateMemberVpitch,
  StateMemberVyaw,
  StateMemberAx,
  StateMemberAy,
  StateMemberAz
};

using StateVector = Eigen::Matrix<double, STATE_SIZE, 1>;
using StateMatrix = Eigen::Matrix<double, STATE_SIZE, STATE_SIZE, Eigen::RowMajor>;

constexpr double MIN_VARIANCE = 1e-9;

double normalizeAngle(double a);

// Negative variances -> their absolute value, tiny ones -> MIN_VARIANCE (as the original).
Eigen::MatrixXd sanitizeCovariance(const Eigen::MatrixXd& cov);

class Ekf
{
public:
  Ekf();
  void setProcessNoiseCovariance(const StateMatrix& q) { q_ = q; }
  void setInitialCovariance(const StateMatrix& p0) { p0_ = p0; }
  const StateMatrix& processNoiseCovariance() const { return q_; }
  const StateMatrix& initialCovariance() const { return p0_; }

  // Zero (or the given) state, the initial covariance, uninitialised, no time.
  void reset();
  void reset(const StateVector& state);

  // (F, J): the transition matrix and its Jacobian at the current state for a step of dt.
  std::pair<StateMatrix, StateMatrix> transfer(double dt) const;

  // Project the state to `time`; the first call only sets the time; no-op for dt <= 0.
  void predict(double time);

  // Filter one measurement of the state members `indices` (size k): initialise from it, or
  // predict to its time and correct. False when rejected by the gate (or not finite).
  bool process(double time, const Eigen::VectorXd& z, const Eigen::MatrixXd& covariance, const Eigen::VectorXi& indices,
               double threshold = std::numeric_limits<double>::infinity());
  bool correct(const Eigen::VectorXd& z, const Eigen::MatrixXd& covariance, const Eigen::VectorXi& indices,
               double threshold = std::numeric_limits<double>::infinity());

  StateVector& state() { return x_; }
  StateMatrix& covariance() { return p_; }
  bool initialized = false;
  bool hasTime = false;
  double lastTime = 0.0;
  long rejected = 0;
  bool nanDetected = false;

private:
  bool correctSequential(const Eigen::VectorXd& z, const Eigen::VectorXd& r, const Eigen::VectorXi& idx,
                         double threshold);
  bool correctBatch(const Eigen::VectorXd& z, const Eigen::MatrixXd& R, const Eigen::VectorXi& idx, double threshold);
  bool commit(StateVector& x, StateMatrix& p);

  StateVector x_;
  StateMatrix p_, q_, p0_;
};
}  // namespace robot_localization

#endif  // ROBOT_LOCALIZATION_EKF_H
