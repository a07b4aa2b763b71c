// Dense Goldfarb–Idnani dual active-set QP solver for a QpProblem (docs/qp.md).
//
//   - Equalities (rows of A, rows of C with l == u, fixed variables) are eliminated once per solve
//     by a blocked Householder QR (dependent rows detected, inconsistent ones reported Infeasible);
//     the dual active-set method then works in their null space, where they are always active.
//   - Inequalities are two-sided rows; bounds are handled as bounds (a bound's normal is a unit
//     vector, so its slack and its product with the factorisation cost O(1) and O(n)).
//   - A semi-definite H is handled by proximal-point regularisation: the reduced Hessian gets ρI
//     and the subproblems min f(x) + ρ/2‖x − x_k‖² are solved until x_k stops moving, each warm
//     started from the previous active set with the same factorisation (the solution is that of
//     the original problem, not of a perturbed one).
//   - Warm start from the previous Optimal active set; on any failure of the warm attempt the
//     solve restarts cold. Every Optimal answer is re-checked against the KKT conditions.
//   - Structured path (structured_path.hpp): a warm solve of a QP whose H is block-diagonal first
//     solves the previous active set directly (bound-fixed variables removed, range space on the
//     blocks) and keeps the answer only if it passes the optimality and KKT checks; otherwise the
//     dense path above runs.
//
// Real-time: solve() is noexcept and does not allocate, lock, throw or print. All memory is sized
// from the capacity given at construction.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "qp/qp_problem.hpp"
#include "qp/qp_status.hpp"
#include "qp/structured_path.hpp"

namespace mrqp::qp {

struct QpSettings {
  /// Add/drop steps allowed per attempt (a failed warm attempt is followed by a cold one).
  /// 0 = automatic: 3·(n + inequality rows + finite bounds) + 50, counted over all proximal
  /// subproblems of the attempt.
  int max_iterations = 0;
  /// Proximal-point outer iterations allowed when the reduced Hessian is regularised.
  int max_proximal_iterations = 300;
  /// Start from the active set of the previous Optimal solve (if it still fits the problem).
  bool warm_start = true;
  /// On a warm start with a block-diagonal H, first try the previous active set on the
  /// structured path (docs/qp.md, "6. The structured path"); false: always the dense path.
  bool structured_path = true;
  /// A constraint counts as violated when its violation exceeds
  /// primal_tolerance · max(1, |bound|, ‖row‖·‖x‖∞).
  double primal_tolerance = 1e-9;
  /// Relative tolerance on multiplier signs and on the proximal step (stationarity).
  double dual_tolerance = 1e-9;
  /// Optimal is reported only if the final scaled KKT residuals (primal violation, stationarity,
  /// complementarity, wrong-sign multipliers) are at most this; otherwise NumericalFailure.
  double kkt_tolerance = 1e-6;
  /// Proximal weight ρ = regularization · (largest diagonal entry of ZᵀHZ, or 1 if that is 0),
  /// used only when the reduced Hessian ZᵀHZ is not safely positive definite (docs/qp.md).
  double regularization = 1e-7;
  /// The reduced Hessian counts as positive definite when every Cholesky pivot exceeds this times
  /// its largest diagonal entry.
  double definiteness_tolerance = 1e-10;
  /// An equality row whose component outside the span of the previous rows is below this
  /// fraction of its norm is treated as dependent (dropped if consistent, Infeasible if not).
  double rank_tolerance = 1e-10;
  /// A constraint normal whose component in the free subspace is below this (relative to
  /// ‖J‖_F·‖normal‖) is treated as linearly dependent on the active constraints.
  double dependency_tolerance = 1e-12;
};

/// What happened in the last solve.
struct QpInfo {
  QpStatus status = QpStatus::NotSolved;
  QpInputError input_error = QpInputError::None;
  int iterations = 0;            ///< add/drop steps, all attempts together
  int proximal_iterations = 0;   ///< outer proximal-point iterations (0 if not regularised)
  bool warm_started = false;     ///< a warm start was attempted (a previous Optimal solve exists)
  bool cold_restarted = false;   ///< the warm attempt failed and the solve restarted cold
  bool regularized = false;      ///< the reduced Hessian needed the proximal term
  double rho = 0.0;              ///< proximal weight used (0 if not regularised)
  int equality_rank = 0;         ///< rank of the equality rows (A, C rows with l == u, fixed x)
  int dependent_equalities = 0;  ///< equality rows dropped as dependent (and consistent)
  int active_inequalities = 0;   ///< rows of C active at a bound (excluding l == u rows)
  int active_bounds = 0;         ///< variable bounds active (excluding fixed variables)
  double objective = 0.0;        ///< ½xᵀHx + gᵀx at the returned x
  double primal_residual = 0.0;  ///< max absolute violation of A x = b, l ≤ Cx ≤ u, xl ≤ x ≤ xu
  double dual_residual = 0.0;    ///< ‖Hx + g + Aᵀy + Cᵀλ + μ‖∞ (absolute)
  double complementarity = 0.0;  ///< max |multiplier · distance to its bound|

  /// The structured path was tried (a warm start of a problem of the same size).
  bool structured_tried = false;
  /// It answered: the previous active set was optimal (iterations 0). When it was tried and did
  /// not answer, `structured_outcome` says why, and the dense path solved.
  bool structured = false;
  StructuredPath::Outcome structured_outcome = StructuredPath::Outcome::NotStructured;
};

class QpSolver {
 public:
  /// Allocates everything a solve of a problem up to this size needs.
  QpSolver(int max_variables, int max_equalities, int max_inequalities,
           const QpSettings& settings = QpSettings());
  /// Capacity taken from the problem's capacity.
  explicit QpSolver(const QpProblem& problem, const QpSettings& settings = QpSettings());

  QpSettings& settings() noexcept { return settings_; }
  const QpSettings& settings() const noexcept { return settings_; }

  int maxVariables() const noexcept { return max_n_; }
  int maxEqualities() const noexcept { return max_me_; }
  int maxInequalities() const noexcept { return max_mi_; }

  /// Solves the problem at its current active size. noexcept, allocation-free.
  QpStatus solve(const QpProblem& problem) noexcept;

  /// Forgets the active set (and proximal centre) kept for the next warm start.
  void resetWarmStart() noexcept;

  const QpInfo& info() const noexcept { return info_; }
  QpStatus status() const noexcept { return info_.status; }
  double objective() const noexcept { return info_.objective; }
  int iterations() const noexcept { return info_.iterations; }

  // Results of the last solve, sized to that problem (meaningful when status() == Optimal).
  // Sign convention: Hx + g + Aᵀy + Cᵀλ + μ = 0, with λ_i ≤ 0 when row i is at its lower bound,
  // λ_i ≥ 0 at its upper bound, 0 when inactive (same for μ and the variable bounds); y is free.
  Eigen::Ref<const Eigen::VectorXd> x() const noexcept { return x_.head(n_); }
  Eigen::Ref<const Eigen::VectorXd> equalityMultipliers() const noexcept { return y_.head(me_); }
  Eigen::Ref<const Eigen::VectorXd> inequalityMultipliers() const noexcept { return lambda_.head(mi_); }
  Eigen::Ref<const Eigen::VectorXd> boundMultipliers() const noexcept { return mu_.head(n_); }

 private:
  // A general row (kind 0) or a variable bound (kind 1), on its lower (+1) or upper (-1) side,
  // written as nᵀx ≥ β with n = side·row, β = side > 0 ? lower : -upper.
  struct Constraint {
    std::int32_t index = 0;
    std::int8_t kind = 0;
    std::int8_t side = 1;
  };
  enum : std::int8_t { kFree = 0, kInequality = 1, kEquality = 2 };

  QpStatus validate(const QpProblem& p) noexcept;
  QpStatus classify() noexcept;
  QpStatus factorEqualities() noexcept;
  void buildBlockReflector(int k0, int nb) noexcept;
  template <class MB>
  void applyBlockReflector(int nb, bool transpose, MB&& M) noexcept;
  QpStatus factorReducedHessian() noexcept;
  // Range-space path, taken when Hs is positive definite with a small profile (a task Hessian:
  // a diagonal plus a few dense blocks): Hs = L Lᵀ by a profile Cholesky (Lᵀ kept in Lz_), the
  // equality normals are factorised as L⁻¹Aeᵀ = QR, and J = L⁻ᵀ Q(:, r:n) directly, with no
  // reduced Hessian to form and factorise (docs/qp.md).
  bool factorHessianProfile() noexcept;
  void solveL(Eigen::Ref<Eigen::VectorXd> v) const noexcept;   // v ← L⁻¹ v
  void solveLt(Eigen::Ref<Eigen::VectorXd> v) const noexcept;  // v ← L⁻ᵀ v
  QpStatus finishRangeSpace() noexcept;
  bool choleskyInPlace(int m, double rho, double threshold) noexcept;
  QpStatus runAttempt(bool warm) noexcept;
  QpStatus iterate() noexcept;
  bool refine() noexcept;
  void startCold() noexcept;
  bool startWarm() noexcept;
  void computeSPair() noexcept;
  bool dropNegativeMultiplier(double tolerance) noexcept;
  void projectOnEqualities() noexcept;
  QpStatus addConstraint(const Constraint& c, bool& abandoned) noexcept;
  void correctActive() noexcept;
  void appendToFactorisation(int q) noexcept;
  void removeFromFactorisation(int k) noexcept;
  void normalTimesJ(const Constraint& c) noexcept;  // d = Jᵀ n
  double normalDot(const Constraint& c, const Eigen::Ref<const Eigen::VectorXd>& v) const noexcept;
  double rhs(const Constraint& c) const noexcept;
  double normalNorm(const Constraint& c) const noexcept;
  void gradient(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> out) const noexcept;
  int chooseViolated() noexcept;
  QpStatus checkKkt() noexcept;
  QpStatus finish(QpStatus status) noexcept;
  bool tryStructured() noexcept;
  void setActive(const Constraint& c, std::int8_t value) noexcept;
  std::int8_t activeSide(const Constraint& c) const noexcept;

  QpSettings settings_;
  int max_n_, max_me_, max_mi_, max_eq_;
  QpInfo info_;
  const QpProblem* p_ = nullptr;

  // sizes of the current solve
  int n_ = 0, me_ = 0, mi_ = 0;
  int meq_ = 0;   // equality rows (A, C with l == u, fixed bounds)
  int rank_ = 0;  // their rank
  int nz_ = 0;    // n - rank: dimension of the free subspace (columns of J)
  int q_ = 0;     // active inequalities/bounds (first q_ columns of J)
  int max_iter_ = 0;
  int iter_ = 0;  // steps of the current attempt
  Constraint cand_;
  bool regularized_ = false;
  double rho_ = 0.0;
  double jnorm_ = 0.0;  // ‖J‖_F

  // problem-derived
  Eigen::MatrixXd Hs_;  // symmetric part of H
  Eigen::VectorXd rownorm_;
  std::vector<std::int8_t> row_kind_, bound_kind_;  // kFree / kInequality / kEquality
  // Envelope of Hs: rows h_lo_[j] … h_hi_[j] hold column j's non-zeros (h_hi_ < h_lo_: empty).
  // A Hessian made of a diagonal and a few dense blocks (the usual task Hessian) then costs
  // O(Σ envelope · nz) instead of O(n² nz) in the reduced Hessian.
  std::vector<std::int32_t> h_lo_, h_hi_;
  long h_envelope_ = 0;
  bool range_space_ = false;
  std::vector<std::int8_t> row_active_, bound_active_;  // 0, +1 lower, -1 upper

  // equalities: Householder QR of Aeᵀ (n × meq), vectors below the diagonal, dependent columns last
  static constexpr int kPanel = 8;  // reflectors per block
  Eigen::MatrixXd QRe_, V_, T_;
  Eigen::VectorXd tau_, colnorm0_, be_, bw1_, bw2_;
  std::vector<std::int32_t> eq_src_;  // per original equality row: encoded source
  std::vector<std::int32_t> perm_;    // column k of QRe_ holds equality row perm_[k]
  Eigen::VectorXd xp_;                // particular solution of the equalities

  // null space, reduced Hessian, J = Z L⁻ᵀ (n × nz), R (q × q upper triangular)
  Eigen::MatrixXd J_, J0_, W_, Hz_, Lz_, R_;

  // active set
  std::vector<Constraint> active_;
  Eigen::VectorXd u_;
  std::vector<Constraint> warm_;
  int warm_count_ = 0;
  int warm_n_ = -1, warm_me_ = -1, warm_mi_ = -1;
  Eigen::VectorXd xprev_;

  // iterates and work vectors
  Eigen::VectorXd x_, xc_, grad_, d_, z_, r_, cx_, t1_, t2_, t3_;
  Eigen::VectorXd y_, lambda_, mu_;
  bool refined_ = false;

  StructuredPath structured_;
};

}  // namespace mrqp::qp
