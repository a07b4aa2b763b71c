// Goldfarb–Idnani dual active-set method (D. Goldfarb, A. Idnani, "A numerically stable dual
// method for solving strictly convex quadratic programs", Math. Programming 27, 1983), written
// from the paper's description, with the equalities eliminated by a null-space basis and
// proximal-point regularisation for a semi-definite Hessian. See docs/qp.md for the derivation
// of every formula used here.
//
// Notation (docs/qp.md): Z is an orthonormal basis of the null space of the equality rows, and
// L Lᵀ = ZᵀHZ (+ρI). J = Z L⁻ᵀ is n × nz; its first q columns span the active constraint normals
// (in the metric of H) and R (q × q, upper triangular) satisfies R = J₁ᵀ N for the active normals
// N; the remaining columns J₂ span the directions that keep every active constraint.
// Every operation below is a matrix–vector product, a rank-one update or a plane rotation on
// preallocated storage: nothing allocates.
#include "qp/qp_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrqp::qp {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Equality-row sources, encoded in one int: which matrix (A, C or a bound) and the index.
constexpr std::int32_t kSrcA = 0;
constexpr std::int32_t kSrcC = 1;
constexpr std::int32_t kSrcBound = 2;
constexpr std::int32_t kSrcShift = 28;
constexpr std::int32_t kSrcMask = (1 << kSrcShift) - 1;
inline std::int32_t encodeSrc(std::int32_t kind, int index) noexcept {
  return (kind << kSrcShift) | static_cast<std::int32_t>(index);
}
inline std::int32_t srcKind(std::int32_t s) noexcept { return s >> kSrcShift; }
inline int srcIndex(std::int32_t s) noexcept { return static_cast<int>(s & kSrcMask); }

// A sum of finite entries is finite unless it overflows, and one NaN or ±inf entry makes the sum
// NaN or ±inf: a finite Σx (one vectorised addition per entry, column by column) proves every
// entry finite. Otherwise x·0, which is 0 for a finite x and NaN for ±inf or NaN, decides.
template <class M>
bool allFinite(const M& m) noexcept {
  if (m.size() == 0) return true;
  double sum = 0.0;
  for (Eigen::Index j = 0; j < m.cols(); ++j) sum += m.col(j).sum();
  return std::isfinite(sum) || (m.array() * 0.0).sum() == 0.0;
}

template <class V>
bool anyNaN(const V& v) noexcept {
  return v.size() > 0 && v.hasNaN();
}

// Householder reflector H = I − τ v vᵀ with v(0) = 1 such that H x = β e₁. On return x(0) = β and
// x(1:) holds v(1:). Returns τ (0 when x(1:) is already zero: H = I, β = x(0)).
template <class V>
double makeHouseholder(V&& x) noexcept {
  const Eigen::Index m = x.size();
  if (m <= 1) return 0.0;
  const double sigma = x.tail(m - 1).squaredNorm();
  if (sigma == 0.0) return 0.0;
  const double x0 = x(0);
  const double mu = std::sqrt(x0 * x0 + sigma);
  const double beta = x0 <= 0.0 ? mu : -mu;
  x.tail(m - 1) /= (x0 - beta);
  x(0) = beta;
  return (beta - x0) / beta;
}

// M ← M (I − τ v vᵀ), v of length M.cols() (v(0) must hold 1), w: work of length M.rows().
template <class MB, class VB, class WB>
void applyHouseholderRight(MB&& M, const VB& v, double tau, WB&& w) noexcept {
  if (tau == 0.0 || M.rows() == 0) return;
  w.noalias() = M * v;
  w *= tau;
  for (Eigen::Index j = 0; j < M.cols(); ++j) M.col(j) -= v(j) * w;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// construction

QpSolver::QpSolver(int max_variables, int max_equalities, int max_inequalities, const QpSettings& settings)
    : settings_(settings),
      max_n_(max_variables),
      max_me_(max_equalities),
      max_mi_(max_inequalities),
      max_eq_(max_equalities + max_inequalities + max_variables),
      structured_(std::max(0, max_variables), std::max(0, max_equalities), std::max(0, max_inequalities)) {
  if (max_variables < 0 || max_equalities < 0 || max_inequalities < 0)
    throw std::invalid_argument("QpSolver: negative capacity");
  if (max_eq_ > kSrcMask) throw std::invalid_argument("QpSolver: capacity too large");
  const int N = max_n_;
  Hs_.setZero(N, N);
  rownorm_.setZero(max_mi_);
  row_kind_.assign(static_cast<std::size_t>(max_mi_), kFree);
  h_lo_.assign(static_cast<std::size_t>(N), 0);
  h_hi_.assign(static_cast<std::size_t>(N), -1);
  row_active_.assign(static_cast<std::size_t>(max_mi_), 0);
  bound_kind_.assign(static_cast<std::size_t>(N), kFree);
  bound_active_.assign(static_cast<std::size_t>(N), 0);
  QRe_.setZero(N, max_eq_);
  tau_.setZero(max_eq_);
  colnorm0_.setZero(max_eq_);
  V_.setZero(N, kPanel);
  T_.setZero(kPanel, kPanel);
  bw1_.setZero(kPanel);
  bw2_.setZero(kPanel);
  be_.setZero(max_eq_);
  eq_src_.assign(static_cast<std::size_t>(max_eq_), 0);
  perm_.assign(static_cast<std::size_t>(max_eq_), 0);
  xp_.setZero(N);
  J_.setZero(N, N);
  J0_.setZero(N, N);
  W_.setZero(N, N);
  Hz_.setZero(N, N);
  Lz_.setZero(N, N);
  R_.setZero(N, N);
  active_.assign(static_cast<std::size_t>(N), Constraint());
  warm_.assign(static_cast<std::size_t>(N), Constraint());
  u_.setZero(N);
  xprev_.setZero(N);
  x_.setZero(N);
  xc_.setZero(N);
  grad_.setZero(N);
  d_.setZero(N);
  z_.setZero(N);
  r_.setZero(N);
  cx_.setZero(max_mi_);
  const int work = std::max(N, max_eq_);
  t1_.setZero(work);
  t2_.setZero(work);
  t3_.setZero(work);
  y_.setZero(max_me_);
  lambda_.setZero(max_mi_);
  mu_.setZero(N);
}

QpSolver::QpSolver(const QpProblem& problem, const QpSettings& settings)
    : QpSolver(problem.maxVariables(), problem.maxEqualities(), problem.maxInequalities(), settings) {}

void QpSolver::resetWarmStart() noexcept {
  warm_count_ = 0;
  warm_n_ = warm_me_ = warm_mi_ = -1;
}

// ---------------------------------------------------------------------------------------------
// small helpers on constraints

double QpSolver::normalDot(const Constraint& c, const Eigen::Ref<const Eigen::VectorXd>& v) const noexcept {
  if (c.kind == 0) return c.side * p_->C().row(c.index).dot(v.head(n_).transpose());
  return c.side * v(c.index);
}

double QpSolver::rhs(const Constraint& c) const noexcept {
  if (c.kind == 0) return c.side > 0 ? p_->l()(c.index) : -p_->u()(c.index);
  return c.side > 0 ? p_->xl()(c.index) : -p_->xu()(c.index);
}

double QpSolver::normalNorm(const Constraint& c) const noexcept {
  return c.kind == 0 ? rownorm_(c.index) : 1.0;
}

void QpSolver::setActive(const Constraint& c, std::int8_t value) noexcept {
  if (c.kind == 0)
    row_active_[static_cast<std::size_t>(c.index)] = value;
  else
    bound_active_[static_cast<std::size_t>(c.index)] = value;
}

std::int8_t QpSolver::activeSide(const Constraint& c) const noexcept {
  return c.kind == 0 ? row_active_[static_cast<std::size_t>(c.index)]
                     : bound_active_[static_cast<std::size_t>(c.index)];
}

void QpSolver::normalTimesJ(const Constraint& c) noexcept {
  if (nz_ == 0) return;
  auto d = d_.head(nz_);
  if (c.kind == 0) {
    d.noalias() = J_.topLeftCorner(n_, nz_).transpose() * p_->C().row(c.index).transpose();
    if (c.side < 0) d = -d;
  } else {
    d = J_.row(c.index).head(nz_).transpose();
    if (c.side < 0) d = -d;
  }
}

void QpSolver::gradient(const Eigen::Ref<const Eigen::VectorXd>& x,
                        Eigen::Ref<Eigen::VectorXd> out) const noexcept {
  out.head(n_).noalias() = Hs_.topLeftCorner(n_, n_) * x.head(n_);
  out.head(n_) += p_->g();
  if (regularized_) out.head(n_) += rho_ * (x.head(n_) - xc_.head(n_));
}

// ---------------------------------------------------------------------------------------------
// solve

QpStatus QpSolver::solve(const QpProblem& problem) noexcept {
  info_ = QpInfo();
  p_ = &problem;
  QpStatus st = validate(problem);
  if (st != QpStatus::Optimal) return finish(st);
  if (tryStructured()) return finish(QpStatus::Optimal);
  st = classify();
  if (st != QpStatus::Optimal) return finish(st);
  range_space_ = factorHessianProfile();
  for (;;) {
    st = factorEqualities();
    if (st != QpStatus::Optimal) return finish(st);
    st = range_space_ ? finishRangeSpace() : factorReducedHessian();
    if (st != QpStatus::Optimal) return finish(st);

    const bool warm = settings_.warm_start && warm_n_ >= 0;
    if (warm) {
      J0_.topLeftCorner(n_, nz_) = J_.topLeftCorner(n_, nz_);
      info_.warm_started = true;
      st = runAttempt(true);
      if (st == QpStatus::Optimal) return finish(st);
      // defined recovery: forget the warm start and solve again from scratch
      info_.cold_restarted = true;
      J_.topLeftCorner(n_, nz_) = J0_.topLeftCorner(n_, nz_);
    }
    st = runAttempt(false);
    // The range-space factors may be less accurate on a badly conditioned H: a failure there is
    // retried once on the null-space path before it is reported.
    if (st != QpStatus::NumericalFailure || !range_space_) return finish(st);
    range_space_ = false;
  }
}

// The structured path from the previous active set (docs/qp.md, "6. The structured path"): only
// for a warm start on a problem of the same size; the remembered constraints that are still
// inequalities with that side finite form the first guess. True when it answered: x_, the
// multipliers, info_ and the active set (active_, q_) are then the solution.
bool QpSolver::tryStructured() noexcept {
  if (!settings_.structured_path || !settings_.warm_start || warm_n_ != n_ || warm_me_ != me_ ||
      warm_mi_ != mi_)
    return false;
  for (int i = 0; i < mi_; ++i) row_active_[static_cast<std::size_t>(i)] = 0;
  for (int j = 0; j < n_; ++j) bound_active_[static_cast<std::size_t>(j)] = 0;
  for (int k = 0; k < warm_count_; ++k) {
    const Constraint c = warm_[static_cast<std::size_t>(k)];
    const bool row = c.kind == 0;
    const double lo = row ? p_->l()(c.index) : p_->xl()(c.index);
    const double up = row ? p_->u()(c.index) : p_->xu()(c.index);
    if (lo == up || !std::isfinite(c.side > 0 ? lo : up)) continue;
    setActive(c, c.side);
  }
  info_.structured_tried = true;
  info_.structured_outcome =
      structured_.solve(*p_, settings_, row_active_.data(), bound_active_.data(), x_.head(n_), y_.head(me_),
                        lambda_.head(mi_), mu_.head(n_), info_);
  if (info_.structured_outcome != StructuredPath::Outcome::Solved) return false;
  q_ = 0;
  for (int i = 0; i < mi_; ++i) {
    const std::int8_t side = row_active_[static_cast<std::size_t>(i)];
    if (side != 0 && p_->l()(i) != p_->u()(i))
      active_[static_cast<std::size_t>(q_++)] = Constraint{static_cast<std::int32_t>(i), 0, side};
  }
  for (int j = 0; j < n_; ++j) {
    const std::int8_t side = bound_active_[static_cast<std::size_t>(j)];
    if (side != 0 && p_->xl()(j) != p_->xu()(j))
      active_[static_cast<std::size_t>(q_++)] = Constraint{static_cast<std::int32_t>(j), 1, side};
  }
  info_.warm_started = true;
  info_.structured = true;
  return true;
}

QpStatus QpSolver::validate(const QpProblem& p) noexcept {
  if (p.n() > max_n_ || p.me() > max_me_ || p.mi() > max_mi_) {
    n_ = me_ = mi_ = 0;
    info_.input_error = QpInputError::CapacityExceeded;
    return QpStatus::InvalidInput;
  }
  n_ = p.n();
  me_ = p.me();
  mi_ = p.mi();
  if (!allFinite(p.H()) || !allFinite(p.g()) || !allFinite(p.A()) || !allFinite(p.b()) || !allFinite(p.C()) ||
      anyNaN(p.l()) || anyNaN(p.u()) || anyNaN(p.xl()) || anyNaN(p.xu())) {
    info_.input_error = QpInputError::NonFiniteData;
    return QpStatus::InvalidInput;
  }
  for (int i = 0; i < mi_; ++i) {
    const double lo = p.l()(i), up = p.u()(i);
    if (lo > up || lo == kInf || up == -kInf) {
      info_.input_error = QpInputError::InvalidBounds;
      return QpStatus::InvalidInput;
    }
  }
  for (int j = 0; j < n_; ++j) {
    const double lo = p.xl()(j), up = p.xu()(j);
    if (lo > up || lo == kInf || up == -kInf) {
      info_.input_error = QpInputError::InvalidBounds;
      return QpStatus::InvalidInput;
    }
  }
  return QpStatus::Optimal;
}

QpStatus QpSolver::classify() noexcept {
  const auto H = p_->H();
  Hs_.topLeftCorner(n_, n_) = 0.5 * (H + H.transpose());
  h_envelope_ = 0;
  for (int j = 0; j < n_; ++j) {
    int lo = 0, hi = n_ - 1;
    while (lo < n_ && Hs_(lo, j) == 0.0) ++lo;
    while (hi >= lo && Hs_(hi, j) == 0.0) --hi;
    h_lo_[static_cast<std::size_t>(j)] = lo;
    h_hi_[static_cast<std::size_t>(j)] = hi;
    h_envelope_ += hi >= lo ? hi - lo + 1 : 0;
  }
  const auto C = p_->C();
  auto rn = rownorm_.head(mi_);
  rn.setZero();
  for (int j = 0; j < n_; ++j) rn += C.col(j).cwiseAbs2();
  rn = rn.cwiseSqrt();

  meq_ = 0;
  for (int i = 0; i < me_; ++i) eq_src_[static_cast<std::size_t>(meq_++)] = encodeSrc(kSrcA, i);
  const double tol = settings_.primal_tolerance;
  for (int i = 0; i < mi_; ++i) {
    const double lo = p_->l()(i), up = p_->u()(i);
    auto& kind = row_kind_[static_cast<std::size_t>(i)];
    row_active_[static_cast<std::size_t>(i)] = 0;
    if (lo == up) {
      kind = kEquality;
      eq_src_[static_cast<std::size_t>(meq_++)] = encodeSrc(kSrcC, i);
    } else if (lo == -kInf && up == kInf) {
      kind = kFree;
    } else if (rn(i) == 0.0) {
      // 0 ∈ [l, u] or nothing can satisfy the row
      if (lo > tol * std::max(1.0, std::abs(lo)) || up < -tol * std::max(1.0, std::abs(up)))
        return QpStatus::Infeasible;
      kind = kFree;
    } else {
      kind = kInequality;
    }
  }
  for (int j = 0; j < n_; ++j) {
    const double lo = p_->xl()(j), up = p_->xu()(j);
    auto& kind = bound_kind_[static_cast<std::size_t>(j)];
    bound_active_[static_cast<std::size_t>(j)] = 0;
    if (lo == up) {
      kind = kEquality;
      eq_src_[static_cast<std::size_t>(meq_++)] = encodeSrc(kSrcBound, j);
    } else if (lo == -kInf && up == kInf) {
      kind = kFree;
    } else {
      kind = kInequality;
    }
  }
  return QpStatus::Optimal;
}

// V_ (rows k0..n) and T_ of the block reflector H_k0 ⋯ H_{k0+nb−1} = I − V T Vᵀ from the
// reflectors stored in QRe_ (LAPACK's "forward, columnwise" compact WY form).
void QpSolver::buildBlockReflector(int k0, int nb) noexcept {
  const int rows = n_ - k0;
  auto V = V_.topLeftCorner(rows, nb);
  for (int i = 0; i < nb; ++i) {
    V.col(i).head(i).setZero();
    V(i, i) = 1.0;
    V.col(i).tail(rows - i - 1) = QRe_.col(k0 + i).segment(k0 + i + 1, rows - i - 1);
  }
  auto T = T_.topLeftCorner(nb, nb);
  T.setZero();
  for (int i = 0; i < nb; ++i) {
    const double tau = tau_(k0 + i);
    T(i, i) = tau;
    if (i > 0 && tau != 0.0) {
      auto t = bw1_.head(i);
      t.noalias() = V.leftCols(i).transpose() * V.col(i);
      bw2_.head(i).noalias() = T.topLeftCorner(i, i) * t;
      T.col(i).head(i) = -tau * bw2_.head(i);
    }
  }
}

// M ← (I − V S Vᵀ) M with S = Tᵀ (transpose: applies Qᵀ of the block) or S = T (applies Q),
// one column of M at a time (two small matrix–vector products per column).
template <class MB>
void QpSolver::applyBlockReflector(int nb, bool transpose, MB&& M) noexcept {
  const auto V = V_.topLeftCorner(M.rows(), nb);
  const auto T = T_.topLeftCorner(nb, nb);
  auto w = bw1_.head(nb);
  auto w2 = bw2_.head(nb);
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    w.noalias() = V.transpose() * M.col(j);
    if (transpose)
      w2.noalias() = T.transpose() * w;
    else
      w2.noalias() = T * w;
    M.col(j).noalias() -= V * w2;
  }
}

// Householder QR of Aeᵀ (n × meq), blocked by panels of kPanel reflectors. A column whose part
// outside the span of the columns already accepted is below rank_tolerance times its own norm is
// dependent: it is moved to the end and takes no reflector, so Aeᵀ P = Q [R₁₁ R₁₂; 0 ≈0] with
// rank r = number of reflectors. (Each row is judged against its own norm, so the decision does
// not depend on how rows are scaled.) Z = Q(:, r:n) and x_p = Q₁ R₁₁⁻ᵀ b_P (minimum norm).
QpStatus QpSolver::factorEqualities() noexcept {
  const int n = n_, m = meq_;
  const auto A = p_->A();
  const auto C = p_->C();
  for (int k = 0; k < m; ++k) {
    const std::int32_t s = eq_src_[static_cast<std::size_t>(k)];
    auto col = QRe_.col(k).head(n);
    const int i = srcIndex(s);
    switch (srcKind(s)) {
      case kSrcA:
        col = A.row(i).transpose();
        be_(k) = p_->b()(i);
        break;
      case kSrcC:
        col = C.row(i).transpose();
        be_(k) = p_->l()(i);
        break;
      default:
        col.setZero();
        col(i) = 1.0;
        be_(k) = p_->xl()(i);
        break;
    }
    if (range_space_) solveL(col);
    perm_[static_cast<std::size_t>(k)] = k;
    colnorm0_(k) = col.norm();
  }

  int r = 0;     // reflectors so far = accepted columns, in positions 0..r-1
  int mend = m;  // columns mend..m-1 are dependent
  while (r < n && r < mend) {
    const int k0 = r;
    // panel: columns are brought up to date with this panel's reflectors one at a time
    while (r - k0 < kPanel && r < n && r < mend) {
      auto col = QRe_.col(r).head(n);
      for (int i = k0; i < r; ++i) {
        auto v = QRe_.col(i).segment(i + 1, n - i - 1);
        double sv = col(i) + v.dot(col.segment(i + 1, n - i - 1));
        sv *= tau_(i);
        col(i) -= sv;
        col.segment(i + 1, n - i - 1) -= sv * v;
      }
      const double rest = col.segment(r, n - r).norm();
      if (!(rest > settings_.rank_tolerance * colnorm0_(r))) {
        --mend;
        if (r != mend) {
          QRe_.col(r).head(n).swap(QRe_.col(mend).head(n));
          std::swap(colnorm0_(r), colnorm0_(mend));
          std::swap(perm_[static_cast<std::size_t>(r)], perm_[static_cast<std::size_t>(mend)]);
        }
        continue;
      }
      tau_(r) = makeHouseholder(QRe_.col(r).segment(r, n - r));
      ++r;
    }
    // trailing columns: Qᵀ of the panel at once, M ← M − V Tᵀ (Vᵀ M)
    if (r > k0 && r < mend) {
      buildBlockReflector(k0, r - k0);
      applyBlockReflector(r - k0, true, QRe_.block(k0, r, n - k0, mend - r));
    }
  }
  rank_ = r;
  nz_ = n - r;
  info_.equality_rank = r;
  info_.dependent_equalities = m - r;

  // particular solution x_p = Q [R₁₁⁻ᵀ b_P; 0]
  auto xp = xp_.head(n);
  xp.setZero();
  if (r > 0) {
    for (int k = 0; k < r; ++k) xp(k) = be_(perm_[static_cast<std::size_t>(k)]);
    QRe_.topLeftCorner(r, r).triangularView<Eigen::Upper>().transpose().solveInPlace(xp.head(r));
    for (int k = r - 1; k >= 0; --k) {
      auto v = QRe_.col(k).segment(k + 1, n - k - 1);
      double s = xp(k) + v.dot(xp.segment(k + 1, n - k - 1));
      s *= tau_(k);
      xp(k) -= s;
      xp.segment(k + 1, n - k - 1) -= s * v;
    }
  }
  if (range_space_) solveLt(xp);  // from y = Lᵀx back to x
  // every equality row, dependent ones included, must hold at x_p
  const double xnorm = xp.size() > 0 ? xp.lpNorm<Eigen::Infinity>() : 0.0;
  for (int k = 0; k < m; ++k) {
    const std::int32_t s = eq_src_[static_cast<std::size_t>(k)];
    const int i = srcIndex(s);
    double ax = 0.0, rn = 1.0, bk = 0.0;
    switch (srcKind(s)) {
      case kSrcA:
        ax = A.row(i).dot(xp.transpose());
        rn = A.row(i).norm();
        bk = p_->b()(i);
        break;
      case kSrcC:
        ax = C.row(i).dot(xp.transpose());
        rn = rownorm_(i);
        bk = p_->l()(i);
        break;
      default:
        ax = xp(i);
        bk = p_->xl()(i);
        break;
    }
    const double scale = std::max({1.0, std::abs(bk), rn * xnorm});
    if (std::abs(ax - bk) > settings_.primal_tolerance * scale) return QpStatus::Infeasible;
  }

  // null-space basis Z = Q(:, r:n) = H₀⋯H_{r−1} [0; I], built in J_ block by block from the last
  auto Z = J_.topLeftCorner(n, nz_);
  if (r > 0) {
    Z.setZero();
    for (int i = 0; i < nz_; ++i) Z(r + i, i) = 1.0;
    for (int k0 = ((r - 1) / kPanel) * kPanel; k0 >= 0; k0 -= kPanel) {
      const int nb = std::min(kPanel, r - k0);
      buildBlockReflector(k0, nb);
      applyBlockReflector(nb, false, J_.block(k0, 0, n - k0, nz_));
    }
  }
  return QpStatus::Optimal;
}

// Cholesky of the lower triangle of Lz_ (+ρ on the diagonal) in place; false if a pivot is not
// above the threshold.
bool QpSolver::choleskyInPlace(int m, double rho, double threshold) noexcept {
  for (int j = 0; j < m; ++j) {
    const double piv = Lz_(j, j) + rho - Lz_.row(j).head(j).squaredNorm();
    if (!(piv > threshold)) return false;
    const double ljj = std::sqrt(piv);
    Lz_(j, j) = ljj;
    if (j + 1 < m) {
      auto below = Lz_.col(j).segment(j + 1, m - j - 1);
      if (j > 0) below.noalias() -= Lz_.block(j + 1, 0, m - j - 1, j) * Lz_.row(j).head(j).transpose();
      below /= ljj;
    }
  }
  return true;
}

// ZᵀHZ, its Cholesky factor (regularised if needed) and J = Z L⁻ᵀ.
QpStatus QpSolver::factorReducedHessian() noexcept {
  const int n = n_, nz = nz_;
  if (rank_ == 0) {
    Hz_.topLeftCorner(n, n).triangularView<Eigen::Lower>() = Hs_.topLeftCorner(n, n);
  } else {
    if (2 * h_envelope_ < static_cast<long>(n) * n) {
      // W = Hs J column of Hs by column: only the envelope of each column is touched.
      auto W = W_.topLeftCorner(n, nz);
      W.setZero();
      for (int j = 0; j < n; ++j) {
        const int lo = h_lo_[static_cast<std::size_t>(j)];
        const int len = h_hi_[static_cast<std::size_t>(j)] - lo + 1;
        if (len <= 0) continue;
        if (len == 1) {
          W.row(lo) += Hs_(lo, j) * J_.row(j).head(nz);
        } else {
          W.middleRows(lo, len).noalias() += Hs_.col(j).segment(lo, len) * J_.row(j).head(nz);
        }
      }
    } else {
      for (int j = 0; j < nz; ++j) W_.col(j).head(n).noalias() = Hs_.topLeftCorner(n, n) * J_.col(j).head(n);
    }
    for (int j = 0; j < nz; ++j)
      Hz_.col(j).segment(j, nz - j).noalias() = J_.block(0, j, n, nz - j).transpose() * W_.col(j).head(n);
  }
  double scale = 0.0;
  for (int j = 0; j < nz; ++j) scale = std::max(scale, Hz_(j, j));

  regularized_ = false;
  rho_ = 0.0;
  Lz_.topLeftCorner(nz, nz).triangularView<Eigen::Lower>() = Hz_.topLeftCorner(nz, nz);
  bool ok = scale > 0.0 && choleskyInPlace(nz, 0.0, settings_.definiteness_tolerance * scale);
  if (nz == 0) ok = true;
  if (!ok) {
    regularized_ = true;
    rho_ = settings_.regularization * (scale > 0.0 ? scale : 1.0);
    Lz_.topLeftCorner(nz, nz).triangularView<Eigen::Lower>() = Hz_.topLeftCorner(nz, nz);
    // H positive semi-definite ⇒ every pivot of ZᵀHZ + ρI is at least ρ (up to rounding)
    if (!choleskyInPlace(nz, rho_, 0.5 * rho_)) {
      info_.input_error = QpInputError::NotConvex;
      return QpStatus::InvalidInput;
    }
  }
  info_.regularized = regularized_;
  info_.rho = rho_;

  // J = Z L⁻ᵀ, column by column: J(:,j) = (Z(:,j) − J(:,0:j) L(j,0:j)ᵀ) / L(j,j)
  if (rank_ == 0) {
    auto J = J_.topLeftCorner(n, n);
    J.setIdentity();
    for (int j = 0; j < n; ++j) {
      if (j > 0) J.col(j).head(j).noalias() -= J.topLeftCorner(j, j) * Lz_.row(j).head(j).transpose();
      J.col(j).head(j + 1) /= Lz_(j, j);
    }
  } else {
    for (int j = 0; j < nz; ++j) {
      if (j > 0) J_.col(j).head(n).noalias() -= J_.topLeftCorner(n, j) * Lz_.row(j).head(j).transpose();
      J_.col(j).head(n) /= Lz_(j, j);
    }
  }
  jnorm_ = J_.topLeftCorner(n, nz).norm();
  return QpStatus::Optimal;
}

// Profile (envelope) Cholesky Hs = L Lᵀ, stored as U = Lᵀ in Lz_ (column i of U = row i of L,
// rows h_lo_[i] … i). Fill-in stays inside the profile. Taken only when the profile is at most
// half of the lower triangle and every pivot is safely positive; false leaves the null-space
// path to handle H (including a semi-definite one).
bool QpSolver::factorHessianProfile() noexcept {
  const int n = n_;
  if (n == 0) return false;
  long profile = 0;
  double scale = 0.0;
  for (int i = 0; i < n; ++i) {
    profile += i - std::min(h_lo_[static_cast<std::size_t>(i)], i) + 1;
    scale = std::max(scale, Hs_(i, i));
  }
  // at most half of the lower triangle (a dense H keeps the null-space path)
  if (4 * profile > static_cast<long>(n) * (n + 1) || !(scale > 0.0)) return false;
  const double threshold = settings_.definiteness_tolerance * scale;
  for (int i = 0; i < n; ++i) {
    const int fi = std::min(h_lo_[static_cast<std::size_t>(i)], i);
    for (int j = fi; j < i; ++j) {
      const int k0 = std::max(fi, std::min(h_lo_[static_cast<std::size_t>(j)], j));
      double sum = Hs_(i, j);
      if (j > k0) sum -= Lz_.col(i).segment(k0, j - k0).dot(Lz_.col(j).segment(k0, j - k0));
      Lz_(j, i) = sum / Lz_(j, j);
    }
    double d = Hs_(i, i);
    if (i > fi) d -= Lz_.col(i).segment(fi, i - fi).squaredNorm();
    if (!(d > threshold)) return false;
    Lz_(i, i) = std::sqrt(d);
  }
  return true;
}

void QpSolver::solveL(Eigen::Ref<Eigen::VectorXd> v) const noexcept {
  for (int i = 0; i < n_; ++i) {
    const int fi = std::min(h_lo_[static_cast<std::size_t>(i)], i);
    double s = v(i);
    if (i > fi) s -= Lz_.col(i).segment(fi, i - fi).dot(v.segment(fi, i - fi));
    v(i) = s / Lz_(i, i);
  }
}

void QpSolver::solveLt(Eigen::Ref<Eigen::VectorXd> v) const noexcept {
  for (int i = n_ - 1; i >= 0; --i) {
    const int fi = std::min(h_lo_[static_cast<std::size_t>(i)], i);
    v(i) /= Lz_(i, i);
    if (i > fi) v.segment(fi, i - fi) -= v(i) * Lz_.col(i).segment(fi, i - fi);
  }
}

// J = L⁻ᵀ Z with Z = Q(:, r:n) from factorEqualities (the identity without equalities):
// JᵀHJ = ZᵀL⁻¹ L Lᵀ L⁻ᵀ Z = I and Ae J = Rᵀ Q₁ᵀ Z = 0, as the null-space path's J.
QpStatus QpSolver::finishRangeSpace() noexcept {
  const int n = n_, nz = nz_;
  auto J = J_.topLeftCorner(n, nz);
  if (rank_ == 0) J.setIdentity();
  for (int i = n - 1; i >= 0; --i) {
    const int fi = std::min(h_lo_[static_cast<std::size_t>(i)], i);
    J.row(i) /= Lz_(i, i);
    if (i > fi) J.middleRows(fi, i - fi).noalias() -= Lz_.col(i).segment(fi, i - fi) * J.row(i);
  }
  regularized_ = false;
  rho_ = 0.0;
  info_.regularized = false;
  info_.rho = 0.0;
  jnorm_ = J.norm();
  return QpStatus::Optimal;
}

// ---------------------------------------------------------------------------------------------
// the dual active-set iterations

QpStatus QpSolver::runAttempt(bool warm) noexcept {
  q_ = 0;
  for (int i = 0; i < mi_; ++i) row_active_[static_cast<std::size_t>(i)] = 0;
  for (int j = 0; j < n_; ++j) bound_active_[static_cast<std::size_t>(j)] = 0;
  int nineq = 0;
  for (int i = 0; i < mi_; ++i) nineq += row_kind_[static_cast<std::size_t>(i)] == kInequality;
  for (int j = 0; j < n_; ++j) nineq += bound_kind_[static_cast<std::size_t>(j)] == kInequality;
  max_iter_ = settings_.max_iterations > 0 ? settings_.max_iterations : 3 * (n_ + nineq) + 50;
  iter_ = 0;

  const bool same_size = warm_n_ == n_;
  if (regularized_) {
    if (warm && same_size)
      xc_.head(n_) = xprev_.head(n_);
    else
      xc_.head(n_) = xp_.head(n_);
  }
  if (warm) {
    if (!startWarm()) return QpStatus::IterationLimit;
  } else {
    startCold();
  }

  int proximal = 0;  // outer iterations of this attempt
  for (;;) {
    const QpStatus st = iterate();
    if (st != QpStatus::Optimal) return st;
    if (!regularized_) break;
    // proximal step converged when ρ‖x − x_c‖ (the stationarity error it causes) is negligible
    t3_.head(n_).noalias() = Hs_.topLeftCorner(n_, n_) * x_.head(n_);
    const double gscale = std::max(
        {1.0, p_->g().lpNorm<Eigen::Infinity>(), n_ > 0 ? t3_.head(n_).lpNorm<Eigen::Infinity>() : 0.0});
    const double step = n_ > 0 ? (x_.head(n_) - xc_.head(n_)).lpNorm<Eigen::Infinity>() : 0.0;
    if (rho_ * step <= settings_.dual_tolerance * gscale) break;
    ++info_.proximal_iterations;
    if (++proximal > settings_.max_proximal_iterations) return QpStatus::IterationLimit;
    xc_.head(n_) = x_.head(n_);
    computeSPair();
    while (dropNegativeMultiplier(settings_.dual_tolerance)) {
      if (++iter_ > max_iter_) return QpStatus::IterationLimit;
      computeSPair();
    }
    refined_ = true;
  }
  return checkKkt();
}

void QpSolver::startCold() noexcept {
  q_ = 0;
  x_.head(n_) = xp_.head(n_);
  computeSPair();
  refined_ = true;
}

bool QpSolver::startWarm() noexcept {
  q_ = 0;
  const bool same_rows = warm_mi_ == mi_;
  const bool same_vars = warm_n_ == n_;
  for (int k = 0; k < warm_count_ && q_ < nz_; ++k) {
    const Constraint c = warm_[static_cast<std::size_t>(k)];
    // keep only constraints that still exist, are inequalities, and have that side finite
    if (c.kind == 0) {
      if (!same_rows || c.index >= mi_ || row_kind_[static_cast<std::size_t>(c.index)] != kInequality)
        continue;
    } else {
      if (!same_vars || c.index >= n_ || bound_kind_[static_cast<std::size_t>(c.index)] != kInequality)
        continue;
    }
    if (activeSide(c) != 0 || !std::isfinite(rhs(c))) continue;
    normalTimesJ(c);
    const double d2 = d_.segment(q_, nz_ - q_).norm();
    if (!(d2 > settings_.dependency_tolerance * jnorm_ * normalNorm(c))) continue;
    appendToFactorisation(q_);
    active_[static_cast<std::size_t>(q_)] = c;
    setActive(c, c.side);
    ++q_;
  }
  x_.head(n_) = xp_.head(n_);
  computeSPair();
  while (dropNegativeMultiplier(settings_.dual_tolerance)) {
    if (++iter_ > max_iter_) return false;
    computeSPair();
  }
  refined_ = true;
  return true;
}

// The minimiser of the (proximal) objective with the active constraints as equalities, and its
// multipliers, computed from the current x (which must satisfy the equality rows):
//   e = β_N − Nᵀx,  v = R⁻ᵀ e,  h = Jᵀ∇f(x),  x ← x + J₁v − J₂h₂,  u = R⁻¹(v + h₁).
void QpSolver::computeSPair() noexcept {
  const int q = q_, nz = nz_, n = n_;
  gradient(x_, grad_);
  for (int k = 0; k < q; ++k) {
    const Constraint& c = active_[static_cast<std::size_t>(k)];
    t1_(k) = rhs(c) - normalDot(c, x_);
  }
  const auto R = R_.topLeftCorner(q, q);
  if (q > 0) R.triangularView<Eigen::Upper>().transpose().solveInPlace(t1_.head(q));
  if (nz > 0) {
    d_.head(nz).noalias() = J_.topLeftCorner(n, nz).transpose() * grad_.head(n);
    t2_.head(q) = t1_.head(q);
    t2_.segment(q, nz - q) = -d_.segment(q, nz - q);
    x_.head(n).noalias() += J_.topLeftCorner(n, nz) * t2_.head(nz);
  }
  if (q > 0) {
    u_.head(q) = t1_.head(q) + d_.head(q);
    R.triangularView<Eigen::Upper>().solveInPlace(u_.head(q));
  }
}

bool QpSolver::dropNegativeMultiplier(double tolerance) noexcept {
  if (q_ == 0) return false;
  int worst = -1;
  double umin = 0.0, umax = 1.0;
  for (int k = 0; k < q_; ++k) {
    umax = std::max(umax, std::abs(u_(k)));
    if (u_(k) < umin) {
      umin = u_(k);
      worst = k;
    }
  }
  if (worst < 0 || umin >= -tolerance * umax) return false;
  removeFromFactorisation(worst);
  return true;
}

// Moves x back onto the equality rows (minimum-norm correction), removing the drift of many
// incremental steps before the final recomputation of x and u.
void QpSolver::projectOnEqualities() noexcept {
  const int r = rank_, n = n_;
  if (r == 0) return;
  const auto A = p_->A();
  const auto C = p_->C();
  auto e = t1_.head(r);
  for (int k = 0; k < r; ++k) {
    const int orig = perm_[static_cast<std::size_t>(k)];
    const std::int32_t s = eq_src_[static_cast<std::size_t>(orig)];
    const int i = srcIndex(s);
    double ax;
    switch (srcKind(s)) {
      case kSrcA:
        ax = A.row(i).dot(x_.head(n).transpose());
        break;
      case kSrcC:
        ax = C.row(i).dot(x_.head(n).transpose());
        break;
      default:
        ax = x_(i);
        break;
    }
    e(k) = be_(orig) - ax;
  }
  QRe_.topLeftCorner(r, r).triangularView<Eigen::Upper>().transpose().solveInPlace(e);
  auto dx = t2_.head(n);
  dx.setZero();
  dx.head(r) = e;
  for (int k = r - 1; k >= 0; --k) {
    auto v = QRe_.col(k).segment(k + 1, n - k - 1);
    double s = dx(k) + v.dot(dx.segment(k + 1, n - k - 1));
    s *= tau_(k);
    dx(k) -= s;
    dx.segment(k + 1, n - k - 1) -= s * v;
  }
  if (range_space_) solveLt(dx);
  x_.head(n) += dx;
}

// Moves x onto the equality rows and the active constraints (x += J₁R⁻ᵀe with e the active
// residuals: Nᵀ J₁ = Rᵀ, and J₁ lies in the null space of the equalities).
void QpSolver::correctActive() noexcept {
  projectOnEqualities();
  const int q = q_;
  if (q == 0) return;
  for (int k = 0; k < q; ++k) {
    const Constraint& c = active_[static_cast<std::size_t>(k)];
    t1_(k) = rhs(c) - normalDot(c, x_);
  }
  R_.topLeftCorner(q, q).triangularView<Eigen::Upper>().transpose().solveInPlace(t1_.head(q));
  x_.head(n_).noalias() += J_.topLeftCorner(n_, q) * t1_.head(q);
}

// The most violated inactive constraint (largest violation divided by the norm of its normal),
// or -1 if none is violated beyond the tolerance. The candidate is left in cand_.
int QpSolver::chooseViolated() noexcept {
  const int n = n_, mi = mi_;
  const double xnorm = n > 0 ? x_.head(n).lpNorm<Eigen::Infinity>() : 0.0;
  const double tol = settings_.primal_tolerance;
  double best = 0.0;
  int found = -1;
  // the most violated constraint, measured as the distance to its bound divided by the norm of
  // its normal (tried and rejected: taking any violated bound first, which avoids computing C x
  // but needs 2–5 times more steps)
  const auto xl = p_->xl();
  const auto xu = p_->xu();
  for (int j = 0; j < n; ++j) {
    if (bound_kind_[static_cast<std::size_t>(j)] != kInequality ||
        bound_active_[static_cast<std::size_t>(j)] != 0)
      continue;
    double viol = xl(j) - x_(j);
    if (viol > 0.0 && viol > tol * std::max(1.0, std::abs(xl(j))) && viol > best) {
      best = viol;
      cand_ = Constraint{static_cast<std::int32_t>(j), 1, 1};
      found = 0;
    }
    viol = x_(j) - xu(j);
    if (viol > 0.0 && viol > tol * std::max(1.0, std::abs(xu(j))) && viol > best) {
      best = viol;
      cand_ = Constraint{static_cast<std::int32_t>(j), 1, -1};
      found = 0;
    }
  }
  if (mi > 0) cx_.head(mi).noalias() = p_->C() * x_.head(n);
  const auto l = p_->l();
  const auto u = p_->u();
  for (int i = 0; i < mi; ++i) {
    if (row_kind_[static_cast<std::size_t>(i)] != kInequality ||
        row_active_[static_cast<std::size_t>(i)] != 0)
      continue;
    const double nrm = rownorm_(i);
    const double cxi = cx_(i);
    double viol = l(i) - cxi;
    if (viol > 0.0 && viol > tol * std::max({1.0, std::abs(l(i)), nrm * xnorm}) && viol / nrm > best) {
      best = viol / nrm;
      cand_ = Constraint{static_cast<std::int32_t>(i), 0, 1};
      found = 0;
    }
    viol = cxi - u(i);
    if (viol > 0.0 && viol > tol * std::max({1.0, std::abs(u(i)), nrm * xnorm}) && viol / nrm > best) {
      best = viol / nrm;
      cand_ = Constraint{static_cast<std::int32_t>(i), 0, -1};
      found = 0;
    }
  }
  return found;
}

QpStatus QpSolver::iterate() noexcept {
  for (;;) {
    if (chooseViolated() < 0) {
      if (refined_) return QpStatus::Optimal;
      // no violation left: recompute x and u on the final active set (iterative refinement)
      if (!refine()) return QpStatus::IterationLimit;
      continue;
    }
    bool abandoned = false;
    const QpStatus st = addConstraint(cand_, abandoned);
    if (abandoned) {
      // the violation was drift: restore the S-pair of the current active set and go on
      if (!refine()) return QpStatus::IterationLimit;
      continue;
    }
    if (st != QpStatus::Optimal) return st;
  }
}

// Removes the drift of many incremental steps: x back onto the equality rows, then x and u
// recomputed from the active set (one step of iterative refinement); negative multipliers are
// dropped. False if the iteration budget ran out.
bool QpSolver::refine() noexcept {
  projectOnEqualities();
  computeSPair();
  while (dropNegativeMultiplier(settings_.dual_tolerance)) {
    if (++iter_ > max_iter_) return false;
    computeSPair();
  }
  refined_ = true;
  return true;
}

// One GI major step: make the violated constraint c active, with partial steps (each dropping an
// active constraint whose multiplier reaches zero) until the full step is possible.
QpStatus QpSolver::addConstraint(const Constraint& c, bool& abandoned) noexcept {
  const double beta = rhs(c);
  const double nn = normalNorm(c);
  double uplus = 0.0;
  bool corrected = false;
  for (;;) {
    if (++iter_ > max_iter_) return QpStatus::IterationLimit;
    ++info_.iterations;
    const int q = q_, nz = nz_, n = n_;
    const double s = normalDot(c, x_) - beta;  // < 0: violated
    normalTimesJ(c);
    const int m = nz - q;
    const double d2n2 = m > 0 ? d_.segment(q, m).squaredNorm() : 0.0;
    const bool dependent = !(std::sqrt(d2n2) > settings_.dependency_tolerance * jnorm_ * nn);
    // dual step direction r = R⁻¹ d₁ and the largest dual step that keeps u ≥ 0
    if (q > 0) {
      r_.head(q) = d_.head(q);
      R_.topLeftCorner(q, q).triangularView<Eigen::Upper>().solveInPlace(r_.head(q));
    }
    double t1 = kInf;
    int kdrop = -1;
    for (int k = 0; k < q; ++k) {
      if (r_(k) > 0.0) {
        const double t = std::max(u_(k), 0.0) / r_(k);
        if (t < t1) {
          t1 = t;
          kdrop = k;
        }
      }
    }
    if (dependent) {
      // no primal direction: the normal is a combination of active normals
      if (kdrop < 0) {
        // A Farkas certificate: the normal is a non-positive combination of active normals (and
        // equality rows), so the constraint cannot hold together with them. Before trusting it,
        // remove the drift of x off the equalities and the active constraints (this changes
        // neither the factorisation nor the multipliers) and look at the violation again.
        if (!corrected) {
          corrected = true;
          correctActive();
          const double sc = normalDot(c, x_) - beta;
          const double xnorm = x_.head(n).lpNorm<Eigen::Infinity>();
          if (-sc <= settings_.primal_tolerance * std::max({1.0, std::abs(beta), nn * xnorm})) {
            abandoned = true;
            return QpStatus::Optimal;
          }
          continue;
        }
        return QpStatus::Infeasible;
      }
      u_.head(q) -= t1 * r_.head(q);
      uplus += t1;
      removeFromFactorisation(kdrop);
      refined_ = false;
      continue;
    }
    // primal step direction z = J₂ d₂ (nᵀz = ‖d₂‖²) and the full step length
    z_.head(n).noalias() = J_.block(0, q, n, m) * d_.segment(q, m);
    const double t2 = -s / d2n2;
    if (t1 < t2) {
      x_.head(n) += t1 * z_.head(n);
      u_.head(q) -= t1 * r_.head(q);
      uplus += t1;
      removeFromFactorisation(kdrop);
      refined_ = false;
      continue;
    }
    x_.head(n) += t2 * z_.head(n);
    refined_ = false;
    if (q > 0) u_.head(q) -= t2 * r_.head(q);
    uplus += t2;
    appendToFactorisation(q);
    active_[static_cast<std::size_t>(q)] = c;
    u_(q) = uplus;
    setActive(c, c.side);
    ++q_;
    return QpStatus::Optimal;
  }
}

// With d = Jᵀn in d_: a reflector on d(q:nz), applied to J(:, q:nz), makes column q of J the new
// active direction; R gains the column [d(0:q); ‖d(q:nz)‖].
void QpSolver::appendToFactorisation(int q) noexcept {
  const int n = n_, m = nz_ - q;
  auto v = d_.segment(q, m);
  const double tau = makeHouseholder(v);
  const double beta = v(0);
  if (tau != 0.0) {
    v(0) = 1.0;
    applyHouseholderRight(J_.block(0, q, n, m), v, tau, t3_.head(n));
    v(0) = beta;
  }
  R_.col(q).head(q) = d_.head(q);
  R_(q, q) = beta;
  if (beta < 0.0) {
    R_(q, q) = -beta;
    J_.col(q).head(n) = -J_.col(q).head(n);
  }
}

// Removes active constraint k: column k of R goes, the Hessenberg part is re-triangularised by
// plane rotations that are applied to the columns of J as well.
void QpSolver::removeFromFactorisation(int k) noexcept {
  const int q = q_, n = n_;
  setActive(active_[static_cast<std::size_t>(k)], 0);
  for (int i = k; i + 1 < q; ++i) {
    active_[static_cast<std::size_t>(i)] = active_[static_cast<std::size_t>(i + 1)];
    u_(i) = u_(i + 1);
  }
  for (int j = k; j + 1 < q; ++j) R_.col(j).head(j + 2) = R_.col(j + 1).head(j + 2);
  for (int j = k; j + 1 < q; ++j) {
    const double a = R_(j, j), b = R_(j + 1, j);
    if (b != 0.0) {
      const double h = std::hypot(a, b);
      const double c = a / h, s = b / h;
      R_(j, j) = h;
      R_(j + 1, j) = 0.0;
      for (int col = j + 1; col + 1 < q; ++col) {
        const double r1 = R_(j, col), r2 = R_(j + 1, col);
        R_(j, col) = c * r1 + s * r2;
        R_(j + 1, col) = -s * r1 + c * r2;
      }
      double* a2 = J_.col(j).data();
      double* b2 = J_.col(j + 1).data();
      for (int i = 0; i < n; ++i) {
        const double ai = a2[i], bi = b2[i];
        a2[i] = c * ai + s * bi;
        b2[i] = c * bi - s * ai;
      }
    }
    R_(j + 1, j) = 0.0;
    if (R_(j, j) < 0.0) {
      for (int col = j; col + 1 < q; ++col) R_(j, col) = -R_(j, col);
      J_.col(j).head(n) = -J_.col(j).head(n);
    }
  }
  --q_;
}

// ---------------------------------------------------------------------------------------------
// multipliers, KKT check, results

QpStatus QpSolver::checkKkt() noexcept {
  const int n = n_, me = me_, mi = mi_;
  const auto A = p_->A();
  const auto C = p_->C();
  auto lam = lambda_.head(mi);
  auto mu = mu_.head(n);
  auto y = y_.head(me);
  lam.setZero();
  mu.setZero();
  y.setZero();
  // active multipliers, projected on u ≥ 0 (a tiny negative value within the dual tolerance is
  // rounding; its size is checked below)
  double sign_error = 0.0, umax = 1.0;
  for (int k = 0; k < q_; ++k) {
    const Constraint& c = active_[static_cast<std::size_t>(k)];
    const double uk = std::max(u_(k), 0.0);
    sign_error = std::max(sign_error, -u_(k));
    umax = std::max(umax, std::abs(u_(k)));
    const double val = -c.side * uk;
    if (c.kind == 0)
      lam(c.index) = val;
    else
      mu(c.index) = val;
  }
  // equality multipliers: least-squares solution of Aeᵀ y_e = −(Hx + g + Cᵀλ + μ)
  auto hx = t3_.head(n);
  hx.noalias() = Hs_.topLeftCorner(n, n) * x_.head(n);
  auto w = t1_.head(n);
  if (mi > 0)
    w.noalias() = C.transpose() * lam;
  else
    w.setZero();
  w += hx + p_->g() + mu;
  w = -w;
  if (range_space_) solveL(w);  // Aeᵀ = L Q R
  const int r = rank_;
  for (int k = 0; k < r; ++k) {
    auto v = QRe_.col(k).segment(k + 1, n - k - 1);
    double s = w(k) + v.dot(w.segment(k + 1, n - k - 1));
    s *= tau_(k);
    w(k) -= s;
    w.segment(k + 1, n - k - 1) -= s * v;
  }
  if (r > 0) QRe_.topLeftCorner(r, r).triangularView<Eigen::Upper>().solveInPlace(w.head(r));
  for (int k = 0; k < r; ++k) {
    const std::int32_t s = eq_src_[static_cast<std::size_t>(perm_[static_cast<std::size_t>(k)])];
    const int i = srcIndex(s);
    switch (srcKind(s)) {
      case kSrcA:
        y(i) = w(k);
        break;
      case kSrcC:
        lam(i) = w(k);
        break;
      default:
        mu(i) = w(k);
        break;
    }
  }
  // stationarity residual Hx + g + Aᵀy + Cᵀλ + μ
  auto res = t2_.head(n);
  auto tmp = grad_.head(n);
  double scale =
      std::max({1.0, n > 0 ? hx.lpNorm<Eigen::Infinity>() : 0.0,
                n > 0 ? p_->g().lpNorm<Eigen::Infinity>() : 0.0, n > 0 ? mu.lpNorm<Eigen::Infinity>() : 0.0});
  res = hx + p_->g() + mu;
  if (me > 0) {
    tmp.noalias() = A.transpose() * y;
    scale = std::max(scale, tmp.lpNorm<Eigen::Infinity>());
    res += tmp;
  }
  if (mi > 0) {
    tmp.noalias() = C.transpose() * lam;
    scale = std::max(scale, tmp.lpNorm<Eigen::Infinity>());
    res += tmp;
  }
  info_.dual_residual = n > 0 ? res.lpNorm<Eigen::Infinity>() : 0.0;
  const double dual_scaled = info_.dual_residual / scale;

  // primal feasibility (relative to the bound only: a scale that grew with ‖x‖ would let a
  // diverged x pass) and complementarity (each multiplier times the distance to its bound)
  double pabs = 0.0, prel = 0.0, comp = 0.0, crel = 0.0;
  auto account = [&](double value, double lo, double up, double m) {
    if (value < lo) {
      pabs = std::max(pabs, lo - value);
      prel = std::max(prel, (lo - value) / std::max(1.0, std::abs(lo)));
    }
    if (value > up) {
      pabs = std::max(pabs, value - up);
      prel = std::max(prel, (value - up) / std::max(1.0, std::abs(up)));
    }
    if (m != 0.0) {
      const double bound = m < 0.0 ? lo : up;
      if (!std::isfinite(bound)) {  // a multiplier on a side that does not exist
        comp = crel = kInf;
        return;
      }
      const double am = std::abs(m), dist = std::abs(value - bound);
      comp = std::max(comp, am * dist);
      crel = std::max(crel, am * dist / (std::max(1.0, am) * std::max(1.0, std::abs(bound))));
    }
  };
  for (int i = 0; i < me; ++i) {
    const double ax = A.row(i).dot(x_.head(n).transpose());
    account(ax, p_->b()(i), p_->b()(i), 0.0);
  }
  if (mi > 0) cx_.head(mi).noalias() = C * x_.head(n);
  for (int i = 0; i < mi; ++i) account(cx_(i), p_->l()(i), p_->u()(i), lam(i));
  for (int j = 0; j < n; ++j) account(x_(j), p_->xl()(j), p_->xu()(j), mu(j));
  info_.primal_residual = pabs;
  info_.complementarity = comp;
  info_.objective = n > 0 ? x_.head(n).dot(0.5 * hx + p_->g()) : 0.0;
  const double tol = settings_.kkt_tolerance;
  if (!(prel <= tol) || !(dual_scaled <= tol) || !(crel <= tol) || !(sign_error <= tol * umax))
    return QpStatus::NumericalFailure;
  return QpStatus::Optimal;
}

QpStatus QpSolver::finish(QpStatus status) noexcept {
  info_.status = status;
  if (status == QpStatus::Optimal) {
    int rows = 0, bounds = 0;
    for (int k = 0; k < q_; ++k) {
      const Constraint& c = active_[static_cast<std::size_t>(k)];
      warm_[static_cast<std::size_t>(k)] = c;
      (c.kind == 0 ? rows : bounds) += 1;
    }
    info_.active_inequalities = rows;
    info_.active_bounds = bounds;
    warm_count_ = q_;
    warm_n_ = n_;
    warm_me_ = me_;
    warm_mi_ = mi_;
    xprev_.head(n_) = x_.head(n_);
  }
  p_ = nullptr;
  return status;
}

}  // namespace mrqp::qp
