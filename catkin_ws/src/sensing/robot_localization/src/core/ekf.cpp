// robot_localization's EKF core; see include/robot_localization/ekf.h.
#include "robot_localization/ekf.h"

#include <cmath>

namespace robot_localization
{
namespace
{
bool isAngle(int i) { return i == StateMemberRoll || i == StateMemberPitch || i == StateMemberYaw; }
}  // namespace

double normalizeAngle(double a)
{
  // Python's (a + pi) % (2 pi) - pi: the result in [-pi, pi)
  const double two_pi = 2.0 * M_PI;
  double m = std::fmod(a + M_PI, two_pi);
  if (m < 0.0)
    m += two_pi;
  return m - M_PI;
}

Eigen::MatrixXd sanitizeCovariance(const Eigen::MatrixXd& cov)
{
  Eigen::MatrixXd out = cov;
  for (Eigen::Index i = 0; i < out.rows() && i < out.cols(); ++i)
    out(i, i) = std::max(std::fabs(out(i, i)), MIN_VARIANCE);
  return out;
}

Ekf::Ekf()
{
  StateVector q;
  q << 0.05, 0.05, 0.06, 0.03, 0.03, 0.06, 0.025, 0.025, 0.04, 0.01, 0.01, 0.02, 0.01, 0.01, 0.015;
  q_ = q.asDiagonal();
  p0_ = StateMatrix::Identity() * 1e-9;
  reset();
}

void Ekf::reset() { reset(StateVector::Zero()); }

void Ekf::reset(const StateVector& state)
{
  x_ = state;
  p_ = p0_;
  initialized = false;
  hasTime = false;
  lastTime = 0.0;
  rejected = 0;
  nanDetected = false;
}

std::pair<StateMatrix, StateMatrix> Ekf::transfer(double dt) const
{
  const double sr = std::sin(x_(StateMemberRoll)), cr = std::cos(x_(StateMemberRoll));
  const double sp = std::sin(x_(StateMemberPitch));
  double cp = std::cos(x_(StateMemberPitch));
  const double sy = std::sin(x_(StateMemberYaw)), cy = std::cos(x_(StateMemberYaw));
  if (std::fabs(cp) <= 1e-9)
    cp = std::copysign(1e-9, cp);
  const double tp = sp / cp, secp = 1.0 / cp;
  Eigen::Matrix3d R;
  R << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
      -sp, cp * sr, cp * cr;
  StateMatrix F = StateMatrix::Identity();
  F.block<3, 3>(0, 6) = R * dt;
  F.block<3, 3>(0, 12) = R * (0.5 * dt * dt);
  F(StateMemberRoll, StateMemberVroll) = dt;
  F(StateMemberRoll, StateMemberVpitch) = sr * tp * dt;
  F(StateMemberRoll, StateMemberVyaw) = cr * tp * dt;
  F(StateMemberPitch, StateMemberVpitch) = cr * dt;
  F(StateMemberPitch, StateMemberVyaw) = -sr * dt;
  F(StateMemberYaw, StateMemberVpitch) = sr * secp * dt;
  F(StateMemberYaw, StateMemberVyaw) = cr * secp * dt;
  F.block<3, 3>(6, 12) = Eigen::Matrix3d::Identity() * dt;

  // the Jacobian: F plus the derivatives of the rotation-dependent terms by roll, pitch, yaw
  const Eigen::Vector3d d = x_.segment<3>(6) * dt + 0.5 * x_.segment<3>(12) * dt * dt;
  Eigen::Matrix3d dR_dr, dR_dp, dR_dy;
  dR_dr << 0.0, cy * sp * cr + sy * sr, -cy * sp * sr + sy * cr, 0.0, sy * sp * cr - cy * sr, -sy * sp * sr - cy * cr,
      0.0, cp * cr, -cp * sr;
  dR_dp << -cy * sp, cy * cp * sr, cy * cp * cr, -sy * sp, sy * cp * sr, sy * cp * cr, -cp, -sp * sr, -sp * cr;
  dR_dy << -sy * cp, -sy * sp * sr - cy * cr, -sy * sp * cr + cy * sr, cy * cp, cy * sp * sr - sy * cr,
      cy * sp * cr + sy * sr, 0.0, 0.0, 0.0;
  StateMatrix J = F;
  J.block<3, 1>(0, StateMemberRoll) += dR_dr * d;
  J.block<3, 1>(0, StateMemberPitch) += dR_dp * d;
  J.block<3, 1>(0, StateMemberYaw) += dR_dy * d;
  const double vp = x_(StateMemberVpitch), vy = x_(StateMemberVyaw);
  J(StateMemberRoll, StateMemberRoll) += (cr * tp * vp - sr * tp * vy) * dt;
  J(StateMemberRoll, StateMemberPitch) += (sr * secp * secp * vp + cr * secp * secp * vy) * dt;
  J(StateMemberPitch, StateMemberRoll) += (-sr * vp - cr * vy) * dt;
  J(StateMemberYaw, StateMemberRoll) += (cr * secp * vp - sr * secp * vy) * dt;
  J(StateMemberYaw, StateMemberPitch) += (sr * vp + cr * vy) * tp * secp * dt;
  return { F, J };
}

void Ekf::predict(double time)
{
  if (!hasTime)
  {
    hasTime = true;
    lastTime = time;
    return;
  }
  const double dt = time - lastTime;
  if (dt <= 0.0)
    return;
  const auto fj = transfer(dt);
  x_ = (fj.first * x_).eval();
  for (int i = StateMemberRoll; i <= StateMemberYaw; ++i)
    x_(i) = normalizeAngle(x_(i));
  p_ = (fj.second * p_ * fj.second.transpose() + q_ * dt).eval();
  lastTime = time;
}

bool Ekf::process(double time, const Eigen::VectorXd& z, const Eigen::MatrixXd& covariance,
                  const Eigen::VectorXi& indices, double threshold)
{
  if (!initialized)
  {
    const Eigen::MatrixXd cov = sanitizeCovariance(covariance);
    for (Eigen::Index a = 0; a < indices.size(); ++a)
    {
      x_(indices(a)) = z(a);
      for (Eigen::Index b = 0; b < indices.size(); ++b)
        p_(indices(a), indices(b)) = cov(a, b);
    }
    initialized = true;
    hasTime = true;
    lastTime = time;
    return true;
  }
  predict(time);
  return correct(z, covariance, indices, threshold);
}

bool Ekf::correct(const Eigen::VectorXd& z, const Eigen::MatrixXd& covariance, const Eigen::VectorXi& indices,
                  double threshold)
{
  const Eigen::MatrixXd R = sanitizeCovariance(covariance);
  const bool diagonal = (R - Eigen::MatrixXd(R.diagonal().asDiagonal())).cwiseAbs().maxCoeff() == 0.0;
  if (R.size() == 0 || diagonal)
    return correctSequential(z, R.diagonal(), indices, threshold);
  return correctBatch(z, R, indices, threshold);
}

bool Ekf::commit(StateVector& x, StateMatrix& p)
{
  if (!x.allFinite() || !p.allFinite())
  {
    nanDetected = true;
    return false;
  }
  for (int i = StateMemberRoll; i <= StateMemberYaw; ++i)
    x(i) = normalizeAngle(x(i));
  x_ = x;
  p_ = p;
  return true;
}

// A diagonal measurement covariance (the usual case) is fused as sequential scalar updates,
// equal to the batch update; the Mahalanobis distance of the whole vector is accumulated on
// the way (the chain rule of the Gaussian likelihood).
bool Ekf::correctSequential(const Eigen::VectorXd& z, const Eigen::VectorXd& r, const Eigen::VectorXi& idx,
                            double threshold)
{
  StateVector x = x_;
  StateMatrix p = p_;
  double sq = 0.0;
  for (Eigen::Index k = 0; k < idx.size(); ++k)
  {
    const int i = idx(k);
    double nu = z(k) - x(i);
    if (isAngle(i))
      nu = normalizeAngle(nu);
    const StateVector pi = p.col(i);
    const double s = pi(i) + r(k);
    if (!(s > 0.0))
      return false;
    sq += nu * nu / s;
    const StateVector gain = pi / s;
    x += gain * nu;
    // Joseph form for a scalar measurement reduces to P - Pi Pi^T / S; symmetry restored below
    p.noalias() -= pi * gain.transpose();
  }
  if (std::isfinite(threshold) && sq >= threshold * threshold)
  {
    ++rejected;
    return false;
  }
  StateMatrix sym = 0.5 * (p + p.transpose());
  return commit(x, sym);
}

bool Ekf::correctBatch(const Eigen::VectorXd& z, const Eigen::MatrixXd& R, const Eigen::VectorXi& idx, double threshold)
{
  const Eigen::Index k = idx.size();
  Eigen::VectorXd innovation(k);
  Eigen::MatrixXd pxh(STATE_SIZE, k);  // P H^T
  for (Eigen::Index a = 0; a < k; ++a)
  {
    innovation(a) = z(a) - x_(idx(a));
    if (isAngle(idx(a)))
      innovation(a) = normalizeAngle(innovation(a));
    pxh.col(a) = p_.col(idx(a));
  }
  Eigen::MatrixXd s(k, k);  // H P H^T + R
  for (Eigen::Index a = 0; a < k; ++a)
    s.row(a) = pxh.row(idx(a));
  s += R;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(s);
  if (!lu.isInvertible())
    return false;
  const Eigen::MatrixXd s_inv = lu.inverse();
  if (std::isfinite(threshold))
  {
    const double sq = innovation.dot(s_inv * innovation);
    if (sq >= threshold * threshold)
    {
      ++rejected;
      return false;
    }
  }
  const Eigen::MatrixXd gain = pxh * s_inv;
  StateVector x = x_ + gain * innovation;
  // Joseph form: (I - KH) P (I - KH)^T + K R K^T
  StateMatrix ikh = StateMatrix::Identity();
  for (Eigen::Index a = 0; a < k; ++a)
    ikh.col(idx(a)) -= gain.col(a);
  StateMatrix p = ikh * p_ * ikh.transpose() + gain * R * gain.transpose();
  return commit(x, p);
}
}  // namespace robot_localization
