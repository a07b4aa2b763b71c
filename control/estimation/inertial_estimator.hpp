// Online estimation of a manipulated entity's parameters (paper 1, Sec. IV): per-link inertial
// parameters φ_link (eq. 47) and per-spring-joint (K, C, O) (eq. 48–49), from the generalised
// force μ = Jᵀ f that the hands' F/T sensors measure (eq. 51), by the Kalman filter of eq. 52–59
// (ParameterKalman); the parameters it reports are the filter's estimate projected onto the
// physically consistent set after every update (the filter's own state is not moved).
//
// Parameter vector (the "full" φ): [φ_link of body 0 … body nb−1, (K, C, O) of each spring joint].
// The filter estimates a chosen subset; the other entries stay at their prior values and their
// contribution is subtracted from μ. Identifiability (docs/estimation.md): mass alone needs a
// non-free-fall acceleration (a − g ≠ 0); the CoM component along a − g is not observable while
// a − g keeps one direction (a box held still): the filter reports it through its covariance;
// the rotational inertia needs angular accelerations or rates in at least two axes.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "estimation/parameter_kalman.hpp"
#include "estimation/physical_consistency.hpp"
#include "estimation/regressor_model.hpp"

namespace mrqp::estimation {

/// What the filter estimates of one body.
enum class BodyEstimate : std::uint8_t {
  None,     ///< known: prior kept
  Mass,     ///< m, with the prior's CoM and inertia about the CoM (φ affine in m)
  MassCom,  ///< m and h = m c, with the prior's rotational inertia about the body origin
  Full,     ///< all 10 parameters
};

struct SpringEstimate {
  int velocity_index = -1;                                     ///< joint coordinate (row of Y)
  Eigen::Vector3d prior = Eigen::Vector3d::Zero();             ///< (K, C, O)
  Eigen::Vector3d prior_std = Eigen::Vector3d::Constant(1.0);  ///< standard deviations of the prior
};

struct EstimatorConfig {
  std::vector<BodyEstimate> bodies;            ///< one per body of the regressor model
  std::vector<InertialVector> body_prior;      ///< prior φ per body (about its origin)
  std::vector<InertialVector> body_prior_std;  ///< prior standard deviation per parameter
  std::vector<ConsistencyBounds> body_bounds;  ///< consistency per body (empty: defaults)
  std::vector<SpringEstimate> springs;
  /// Observation covariance R (nv × nv) of μ, from the F/T sensors' noise mapped by Jᵀ.
  Eigen::MatrixXd observation_covariance;
  /// Process noise: standard deviation per update, relative to the prior's (Q = (ratio·σ₀)²).
  double process_noise_ratio = 1e-4;
};

class InertialEstimator {
 public:
  /// Throws std::invalid_argument on inconsistent sizes, nothing to estimate, non-finite or
  /// non-positive prior deviations, or R not symmetric positive definite.
  InertialEstimator(RegressorModel& model, const EstimatorConfig& config);

  /// One filter step at the entity's (q, v, a) with the measured generalised force μ. Returns
  /// false when the step was rejected (non-finite input, S not positive definite): the estimate
  /// is then unchanged. Allocation-free.
  bool update(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
              const Eigen::Ref<const Eigen::VectorXd>& a,
              const Eigen::Ref<const Eigen::VectorXd>& mu) noexcept;

  /// The full parameter vector (estimated entries from the filter, the others their priors).
  const Eigen::VectorXd& parameters() const noexcept { return full_; }
  /// Parameters of body b (about its origin).
  InertialVector bodyParameters(int b) const noexcept { return full_.segment<10>(10 * b); }
  /// Standard deviation of each full parameter (0 for entries not estimated).
  Eigen::VectorXd standardDeviations() const;
  /// φ = offset + basis θ: how the filter's state θ maps to the full vector.
  const Eigen::MatrixXd& basis() const noexcept { return basis_; }
  const ParameterKalman& filter() const noexcept { return kalman_; }
  /// The regression of the last accepted update in the filter's own coordinates θ:
  /// lastObservation() = lastRegressor() θ + v, i.e. (Y basis, μ − Y offset). For the batch tool.
  const Eigen::MatrixXd& lastRegressor() const noexcept { return Ysel_; }
  const Eigen::VectorXd& lastObservation() const noexcept { return mu_adj_; }
  int rejectedUpdates() const noexcept { return rejected_; }
  /// Updates after which the reported parameters differ from the filter's (a projection acted).
  int projections() const noexcept { return projections_; }

 private:
  void writeBack() noexcept;

  RegressorModel& model_;
  EstimatorConfig config_;
  // full φ = offset_ + basis_ θ, θ the filter's state.
  Eigen::VectorXd offset_, full_, mu_adj_;
  Eigen::MatrixXd basis_, Ylinks_, Yfull_, Ysel_;
  ParameterKalman kalman_;
  int rejected_ = 0;
  int projections_ = 0;
};

}  // namespace mrqp::estimation
