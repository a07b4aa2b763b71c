// Online inertial-parameter estimation (see the header).
#include "estimation/inertial_estimator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mrqp::estimation {
namespace {

Eigen::Matrix3d parallelAxis(double m, const Eigen::Vector3d& c) {
  return m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
}

InertialVector inertiaEntries(const Eigen::Matrix3d& I) {
  InertialVector out = InertialVector::Zero();
  out(4) = I(0, 0);
  out(5) = I(0, 1);
  out(6) = I(1, 1);
  out(7) = I(0, 2);
  out(8) = I(1, 2);
  out(9) = I(2, 2);
  return out;
}

int thetaCount(const EstimatorConfig& config) {
  int p = 3 * static_cast<int>(config.springs.size());
  for (BodyEstimate e : config.bodies)
    p += e == BodyEstimate::Full ? 10 : e == BodyEstimate::MassCom ? 4 : e == BodyEstimate::Mass ? 1 : 0;
  return p;
}

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("InertialEstimator: " + what);
}

}  // namespace

InertialEstimator::InertialEstimator(RegressorModel& model, const EstimatorConfig& config)
    : model_(model), config_(config), kalman_(std::max(thetaCount(config), 1), model.velocityCount()) {
  const int nb = model.bodyCount();
  const int nv = model.velocityCount();
  const int ns = static_cast<int>(config.springs.size());
  const int nfull = 10 * nb + 3 * ns;
  const int p = thetaCount(config);
  check(p > 0, "nothing to estimate");
  check(static_cast<int>(config.bodies.size()) == nb, "one BodyEstimate per body of the model expected");
  check(static_cast<int>(config.body_prior.size()) == nb &&
            static_cast<int>(config.body_prior_std.size()) == nb,
        "one prior and one prior deviation per body expected");
  if (config_.body_bounds.empty())
    config_.body_bounds.assign(static_cast<std::size_t>(nb), ConsistencyBounds{});
  check(static_cast<int>(config_.body_bounds.size()) == nb, "one consistency bound per body expected");
  check(config.observation_covariance.rows() == nv && config.observation_covariance.cols() == nv,
        "observation covariance must be nv x nv");
  const Eigen::LLT<Eigen::MatrixXd> r_llt(config.observation_covariance);
  check(config.observation_covariance.allFinite() && r_llt.info() == Eigen::Success &&
            config.observation_covariance.isApprox(config.observation_covariance.transpose()),
        "observation covariance must be symmetric positive definite");
  check(std::isfinite(config.process_noise_ratio) && config.process_noise_ratio >= 0.0,
        "process noise ratio must be finite and non-negative");

  offset_ = Eigen::VectorXd::Zero(nfull);
  basis_ = Eigen::MatrixXd::Zero(nfull, p);
  Eigen::VectorXd theta0(p), sigma0(p);
  int k = 0;
  for (int b = 0; b < nb; ++b) {
    const InertialVector& prior = config.body_prior[static_cast<std::size_t>(b)];
    const InertialVector& sd = config.body_prior_std[static_cast<std::size_t>(b)];
    check(prior.allFinite(), "prior of body " + std::to_string(b) + " is not finite");
    const BodyEstimate e = config.bodies[static_cast<std::size_t>(b)];
    const int base = 10 * b;
    switch (e) {
      case BodyEstimate::None:
        offset_.segment<10>(base) = prior;
        break;
      case BodyEstimate::Mass: {
        check(prior(0) > 0.0, "body " + std::to_string(b) + ": a Mass estimate needs a positive prior mass");
        const double m0 = prior(0);
        const Eigen::Vector3d c = prior.segment<3>(1) / m0;
        Eigen::Matrix3d Io;
        Io << prior(4), prior(5), prior(7), prior(5), prior(6), prior(8), prior(7), prior(8), prior(9);
        const Eigen::Matrix3d Ic = Io - parallelAxis(m0, c);
        offset_.segment<10>(base) = inertiaEntries(Ic);
        InertialVector d = inertiaEntries(parallelAxis(1.0, c));
        d(0) = 1.0;
        d.segment<3>(1) = c;
        basis_.block(base, k, 10, 1) = d;
        theta0(k) = m0;
        sigma0(k) = sd(0);
        ++k;
        break;
      }
      case BodyEstimate::MassCom:
        offset_.segment<6>(base + 4) = prior.tail<6>();
        for (int i = 0; i < 4; ++i, ++k) {
          basis_(base + i, k) = 1.0;
          theta0(k) = prior(i);
          sigma0(k) = sd(i);
        }
        break;
      case BodyEstimate::Full:
        for (int i = 0; i < 10; ++i, ++k) {
          basis_(base + i, k) = 1.0;
          theta0(k) = prior(i);
          sigma0(k) = sd(i);
        }
        break;
    }
  }
  for (int s = 0; s < ns; ++s) {
    const SpringEstimate& spring = config.springs[static_cast<std::size_t>(s)];
    check(spring.velocity_index >= 0 && spring.velocity_index < nv,
          "spring " + std::to_string(s) + ": velocity index out of range");
    check(spring.prior.allFinite(), "spring " + std::to_string(s) + ": prior not finite");
    for (int i = 0; i < 3; ++i, ++k) {
      basis_(10 * nb + 3 * s + i, k) = 1.0;
      theta0(k) = spring.prior(i);
      sigma0(k) = spring.prior_std(i);
    }
  }
  check(sigma0.allFinite() && sigma0.minCoeff() > 0.0,
        "prior standard deviations must be finite and positive");
  kalman_.reset(theta0, sigma0.cwiseAbs2().asDiagonal().toDenseMatrix());
  kalman_.setProcessNoise((config.process_noise_ratio * sigma0).cwiseAbs2());
  full_ = offset_ + basis_ * theta0;
  mu_adj_.resize(nv);
  Ylinks_.resize(nv, 10 * nb);
  Yfull_ = Eigen::MatrixXd::Zero(nv, nfull);
  Ysel_.resize(nv, p);
}

bool InertialEstimator::update(const Eigen::Ref<const Eigen::VectorXd>& q,
                               const Eigen::Ref<const Eigen::VectorXd>& v,
                               const Eigen::Ref<const Eigen::VectorXd>& a,
                               const Eigen::Ref<const Eigen::VectorXd>& mu) noexcept {
  const int nb = model_.bodyCount();
  if (!q.allFinite() || !v.allFinite() || !a.allFinite() || !mu.allFinite() || mu.size() != Yfull_.rows()) {
    ++rejected_;
    return false;
  }
  model_.linkRegressor(q, v, a, Ylinks_);
  Yfull_.leftCols(10 * nb) = Ylinks_;
  for (std::size_t s = 0; s < config_.springs.size(); ++s) {
    // The joint feels −(K q + C q̇ + O): on the left of the EoM with Y φ = Jᵀ f.
    const int j = config_.springs[s].velocity_index;
    const Eigen::Index col = 10 * nb + 3 * static_cast<Eigen::Index>(s);
    Yfull_(j, col) = q(j);  // fixed-base mechanisms without mimic joints: q and v share indices
    Yfull_(j, col + 1) = v(j);
    Yfull_(j, col + 2) = 1.0;
  }
  mu_adj_ = mu;
  mu_adj_.noalias() -= Yfull_ * offset_;
  Ysel_.noalias() = Yfull_ * basis_;
  if (!kalman_.update(Ysel_, mu_adj_, config_.observation_covariance)) {
    ++rejected_;
    return false;
  }
  writeBack();
  return true;
}

void InertialEstimator::writeBack() noexcept {
  // The reported parameters: the filter's estimate mapped to the full vector, each body projected
  // onto the consistent set. The filter's own state is left as it is: moving it would bias every
  // later update, since its covariance knows nothing of the projection.
  full_ = offset_;
  full_.noalias() += basis_ * kalman_.estimate();
  bool changed = false;
  for (std::size_t b = 0; b < config_.bodies.size(); ++b) {
    if (config_.bodies[b] == BodyEstimate::None) continue;
    const ConsistencyBounds& bounds = config_.body_bounds[b];
    const Eigen::Index base = 10 * static_cast<Eigen::Index>(b);
    InertialVector phi = full_.segment<10>(base);
    if (config_.bodies[b] == BodyEstimate::Full) {
      changed = projectPhysicallyConsistent(phi, bounds) || changed;
    } else {
      // Mass / MassCom: the mass floor and the CoM box; the known part of the inertia stays.
      const double m = phi(0) >= bounds.min_mass ? phi(0) : bounds.min_mass;
      Eigen::Vector3d c = phi.segment<3>(1) / phi(0);
      if (bounds.bound_com) c = c.cwiseMax(bounds.com_lower).cwiseMin(bounds.com_upper);
      if (m != phi(0) || (bounds.bound_com && c != phi.segment<3>(1) / phi(0))) {
        phi(0) = m;
        phi.segment<3>(1) = m * c;
        changed = true;
      }
    }
    full_.segment<10>(base) = phi;
  }
  if (changed) ++projections_;
}

Eigen::VectorXd InertialEstimator::standardDeviations() const {
  const Eigen::MatrixXd cov = basis_ * kalman_.covariance() * basis_.transpose();
  return cov.diagonal().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace mrqp::estimation
