// The structured path of QpSolver: a guessed active set solved by the range-space method on a
// block-diagonal Hessian with the bound-fixed variables removed, accepted only when it passes the
// optimality and KKT checks (structured_path.hpp, docs/qp.md "6. The structured path").
//
// Factors are kept as L = L̃ D (L̃ unit lower triangular inside the blocks of size > 1, D the
// diagonal of L): L⁻¹v = D⁻¹(L̃⁻¹v) and L⁻ᵀv = L̃⁻ᵀ(D⁻¹v), so the 1×1 blocks, nearly all of them
// in a controller's Hessian, cost one vectorised scaling. Every column of W = L⁻¹E_Fᵀ is non-zero
// only on a range [first, last] of the free variables (an equality row touches one or two
// entities' accelerations and a few contacts' λ); the products with W and S = WᵀW work on those
// ranges only.
#include "qp/structured_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "qp/qp_solver.hpp"

namespace mrqp::qp {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A pivot of S = E H⁻¹ Eᵀ below this fraction of its diagonal entry means the row's part outside
// the span of the previous rows is below 1e-5 of its norm (in the metric of H⁻¹): too close to
// dependence for the normal equations, so the rank-revealing dense path decides.
constexpr double kDependentPivot = 1e-10;

// Changes of the guessed active set before the dense path takes over, and constraints added or
// released in one change: the path is for an active set that moves a little between control
// cycles; a large move (which would also risk an over-determined guess) is the dense path's work.
constexpr int kMaxGuessChanges = 3;
constexpr int kMaxChangesPerGuess = 4;

// Refinement steps on the KKT residual (each costs a few matrix–vector products), taken while the
// stationarity (relative to its terms) or an equality or active row (relative to max(1, |rhs|))
// is off by more than kRefineTarget: the accuracy of the dense path's answers. An answer still
// off by more than kAccurate after them is left to the dense path (which refines from its own
// factorisation), so the structured path never returns a less accurate optimum.
constexpr int kMaxRefinements = 2;
constexpr double kRefineTarget = 1e-12;
constexpr double kAccurate = 1e-10;

// Whether any of p[0..len) is non-zero (NaN counts as non-zero): the bits of all entries or-ed
// together, sign bit left out (−0 is zero); one vectorised integer operation per entry.
bool anyNonZero(const double* p, Eigen::Index len) noexcept {
  std::uint64_t bits = 0;
  for (Eigen::Index i = 0; i < len; ++i) {
    std::uint64_t b;
    std::memcpy(&b, p + i, sizeof b);
    bits |= b;
  }
  return (bits & ~(std::uint64_t{1} << 63)) != 0;
}

// In-place Cholesky of the lower triangle of M; false if a pivot is not above the threshold.
template <class MB>
bool choleskyLower(MB&& M, double threshold) noexcept {
  const Eigen::Index m = M.rows();
  for (Eigen::Index j = 0; j < m; ++j) {
    const double piv = M(j, j) - M.row(j).head(j).squaredNorm();
    if (!(piv > threshold)) return false;
    const double ljj = std::sqrt(piv);
    M(j, j) = ljj;
    if (j + 1 < m) {
      auto below = M.col(j).segment(j + 1, m - j - 1);
      if (j > 0) below.noalias() -= M.block(j + 1, 0, m - j - 1, j) * M.row(j).head(j).transpose();
      below /= ljj;
    }
  }
  return true;
}

}  // namespace

StructuredPath::StructuredPath(int max_variables, int max_equalities, int max_inequalities)
    : max_n_(max_variables),
      max_me_(max_equalities),
      max_mi_(max_inequalities),
      max_e_(max_equalities + max_inequalities) {
  if (max_variables < 0 || max_equalities < 0 || max_inequalities < 0)
    throw std::invalid_argument("StructuredPath: negative capacity");
  const int N = max_n_;
  const auto uN = static_cast<std::size_t>(N);
  const auto uE = static_cast<std::size_t>(max_e_);
  block_start_.assign(uN + 1, 0);
  lo_.assign(uN, 0);
  hi_.assign(uN, 0);
  multi_.assign(uN, 0);
  fmulti_.assign(uN, 0);
  fmulti_size_.assign(uN, 0);
  free_.assign(uN, 0);
  pos_.assign(uN, -1);
  bound_list_.assign(uN, 0);
  esrc_.assign(uE, 0);
  first_.assign(uE, 0);
  last_.assign(uE, -1);
  Lh_.setZero(N, N);
  Lf_.setZero(N, N);
  dinv_.setZero(N);
  W_.setZero(N, max_e_);
  S_.setZero(max_e_, max_e_);
  xb_.setZero(N);
  e_.setZero(max_e_);
  nu_.setZero(max_e_);
  dnu_.setZero(max_e_);
  re_.setZero(max_e_);
  xf_.setZero(N);
  dxf_.setZero(N);
  rf_.setZero(N);
  hx_.setZero(N);
  aty_.setZero(N);
  ctl_.setZero(N);
  res_.setZero(N);
  cx_.setZero(max_mi_);
  ax_.setZero(max_me_);
}

// ---------------------------------------------------------------------------------------------
// the block partition of H

// Every entry of H outside the blocks of the kept partition is zero.
bool StructuredPath::blocksHold(const QpProblem::ConstMatrixRef& H) const noexcept {
  const int n = static_cast<int>(H.rows());
  for (int k = 0; k < nb_; ++k) {
    const int s = block_start_[static_cast<std::size_t>(k)];
    const int e = block_start_[static_cast<std::size_t>(k) + 1];
    for (int j = s; j < e; ++j) {
      const double* col = H.col(j).data();
      if (anyNonZero(col, s) || anyNonZero(col + e, n - e)) return false;
    }
  }
  return true;
}

// The finest partition of 0..n−1 into consecutive blocks such that every non-zero H(i, j) has i
// and j in one block: a block may end after k when no column j ≤ k reaches a row below k and no
// column j > k reaches a row above k + 1.
void StructuredPath::detectBlocks(const QpProblem::ConstMatrixRef& H) noexcept {
  const int n = static_cast<int>(H.rows());
  for (int j = 0; j < n; ++j) {
    int lo = 0, hi = n - 1;
    while (lo < j && H(lo, j) == 0.0) ++lo;
    while (hi > j && H(hi, j) == 0.0) --hi;
    lo_[static_cast<std::size_t>(j)] = lo;
    hi_[static_cast<std::size_t>(j)] = hi;
  }
  for (int j = n - 2; j >= 0; --j)  // suffix minimum of lo
    lo_[static_cast<std::size_t>(j)] =
        std::min(lo_[static_cast<std::size_t>(j)], lo_[static_cast<std::size_t>(j) + 1]);
  nb_ = 0;
  nmulti_ = 0;
  largest_ = 0;
  block_start_[0] = 0;
  int reach = -1;
  double cubes = 0.0;
  for (int k = 0; k < n; ++k) {
    reach = std::max(reach, hi_[static_cast<std::size_t>(k)]);
    if (reach <= k && (k == n - 1 || lo_[static_cast<std::size_t>(k) + 1] > k)) {
      const int s = block_start_[static_cast<std::size_t>(nb_)];
      const int b = k + 1 - s;
      if (b > 1) multi_[static_cast<std::size_t>(nmulti_++)] = nb_;
      largest_ = std::max(largest_, b);
      cubes += static_cast<double>(b) * b * b;
      block_start_[static_cast<std::size_t>(++nb_)] = k + 1;
    }
  }
  part_n_ = n;
  // the block Cholesky costs at most a quarter of a dense one
  structured_ = 4.0 * cubes <= static_cast<double>(n) * n * n;
}

// H = L Lᵀ block by block (the symmetric part of each block): proves H positive definite, so
// that the KKT conditions of the guessed active set are sufficient for optimality.
bool StructuredPath::factorFullBlocks(const QpProblem::ConstMatrixRef& H, double threshold) noexcept {
  const int n = static_cast<int>(H.rows());
  // 1×1 blocks: the diagonal, checked at once
  for (int j = 0; j < n; ++j)
    if (!(H(j, j) > threshold)) return false;
  for (int m = 0; m < nmulti_; ++m) {
    const int k = multi_[static_cast<std::size_t>(m)];
    const int s = block_start_[static_cast<std::size_t>(k)];
    const int b = block_start_[static_cast<std::size_t>(k) + 1] - s;
    auto L = Lh_.block(s, s, b, b);
    L.triangularView<Eigen::Lower>() = 0.5 * (H.block(s, s, b, b) + H.block(s, s, b, b).transpose());
    if (!choleskyLower(L, threshold)) return false;
  }
  return true;
}

// H_FF = L Lᵀ over the free variables, kept as L̃ D (see the top of the file). A block without
// fixed variables takes its factor from the full one.
bool StructuredPath::factorFreeBlocks(const QpProblem::ConstMatrixRef& H, double threshold) noexcept {
  nfmulti_ = 0;
  // 1×1 factors of every free variable; the multi-blocks below overwrite theirs
  for (int f = 0; f < nf_; ++f)
    dinv_(f) = 1.0 / std::sqrt(H(free_[static_cast<std::size_t>(f)], free_[static_cast<std::size_t>(f)]));
  for (int m = 0; m < nmulti_; ++m) {
    const int k = multi_[static_cast<std::size_t>(m)];
    const int s = block_start_[static_cast<std::size_t>(k)];
    const int e = block_start_[static_cast<std::size_t>(k) + 1];
    // free variables of the block: F indices fs .. fs + b − 1 (free_ is sorted)
    int fs = -1, b = 0;
    for (int j = s; j < e; ++j) {
      const int f = pos_[static_cast<std::size_t>(j)];
      if (f < 0) continue;
      if (fs < 0) fs = f;
      ++b;
    }
    if (b <= 1) continue;  // none, or a 1×1 factor (already in dinv_)
    auto L = Lf_.block(fs, fs, b, b);
    if (b == e - s) {
      L.triangularView<Eigen::Lower>() = Lh_.block(s, s, b, b);
    } else {
      for (int c = 0; c < b; ++c) {
        const int jc = free_[static_cast<std::size_t>(fs + c)];
        for (int r = c; r < b; ++r) {
          const int jr = free_[static_cast<std::size_t>(fs + r)];
          L(r, c) = 0.5 * (H(jr, jc) + H(jc, jr));
        }
      }
      if (!choleskyLower(L, threshold)) return false;
    }
    // L = L̃ D
    for (int c = 0; c < b; ++c) {
      const double d = L(c, c);
      dinv_(fs + c) = 1.0 / d;
      L.col(c).tail(b - c - 1) /= d;
    }
    fmulti_[static_cast<std::size_t>(nfmulti_)] = fs;
    fmulti_size_[static_cast<std::size_t>(nfmulti_++)] = b;
  }
  return true;
}

// v ← L⁻¹ v = D⁻¹ L̃⁻¹ v for a v that is zero outside [first, last]; last grows to the end of the
// block that holds it (the fill of the unit lower triangle).
void StructuredPath::solveL(Eigen::Ref<Eigen::VectorXd> v, int first, int& last) const noexcept {
  if (last < first) return;
  for (int m = 0; m < nfmulti_; ++m) {
    const int s = fmulti_[static_cast<std::size_t>(m)];
    const int b = fmulti_size_[static_cast<std::size_t>(m)];
    if (s + b - 1 < first) continue;
    if (s > last) break;
    for (int c = 0; c + 1 < b; ++c)
      v.segment(s + c + 1, b - c - 1) -= v(s + c) * Lf_.col(s + c).segment(s + c + 1, b - c - 1);
    last = std::max(last, s + b - 1);
  }
  v.segment(first, last - first + 1).array() *= dinv_.segment(first, last - first + 1).array();
}

// v ← L⁻ᵀ v = L̃⁻ᵀ D⁻¹ v over all free variables.
void StructuredPath::solveLt(Eigen::Ref<Eigen::VectorXd> v) const noexcept {
  v.head(nf_).array() *= dinv_.head(nf_).array();
  for (int m = 0; m < nfmulti_; ++m) {
    const int s = fmulti_[static_cast<std::size_t>(m)];
    const int b = fmulti_size_[static_cast<std::size_t>(m)];
    for (int c = b - 2; c >= 0; --c)
      v(s + c) -= Lf_.col(s + c).segment(s + c + 1, b - c - 1).dot(v.segment(s + c + 1, b - c - 1));
  }
}

// out = ½(H + Hᵀ) v, block by block.
void StructuredPath::hessianTimes(const QpProblem::ConstMatrixRef& H,
                                  const Eigen::Ref<const Eigen::VectorXd>& v,
                                  Eigen::Ref<Eigen::VectorXd> out) const noexcept {
  const int n = static_cast<int>(H.rows());
  out.head(n) = H.diagonal().cwiseProduct(v.head(n));
  for (int m = 0; m < nmulti_; ++m) {
    const int k = multi_[static_cast<std::size_t>(m)];
    const int s = block_start_[static_cast<std::size_t>(k)];
    const int b = block_start_[static_cast<std::size_t>(k) + 1] - s;
    const auto B = H.block(s, s, b, b);
    out.segment(s, b).noalias() = 0.5 * (B * v.segment(s, b));
    out.segment(s, b).noalias() += 0.5 * (B.transpose() * v.segment(s, b));
  }
}

// The KKT system of the free variables, H_FF x + E_Fᵀ ν = −rf, E_F x = re, by the range space:
// z = L⁻¹ rf, S ν = −re − Wᵀz, x = −L⁻ᵀ(z + W ν). rf (F space) is overwritten.
void StructuredPath::solveKkt(Eigen::Ref<Eigen::VectorXd> rf, const Eigen::Ref<const Eigen::VectorXd>& re,
                              Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<Eigen::VectorXd> nu) const noexcept {
  int last = nf_ - 1;
  solveL(rf, 0, last);
  for (int r = 0; r < ne_; ++r) {
    const int a = first_[static_cast<std::size_t>(r)];
    const int len = last_[static_cast<std::size_t>(r)] - a + 1;
    nu(r) = -re(r) - (len > 0 ? W_.col(r).segment(a, len).dot(rf.segment(a, len)) : 0.0);
  }
  if (ne_ > 0) {
    const auto U = S_.topLeftCorner(ne_, ne_);
    U.triangularView<Eigen::Upper>().transpose().solveInPlace(nu.head(ne_));
    U.triangularView<Eigen::Upper>().solveInPlace(nu.head(ne_));
  }
  x.head(nf_) = rf.head(nf_);
  for (int r = 0; r < ne_; ++r) {
    const int a = first_[static_cast<std::size_t>(r)];
    const int len = last_[static_cast<std::size_t>(r)] - a + 1;
    if (len > 0) x.segment(a, len) += nu(r) * W_.col(r).segment(a, len);
  }
  solveLt(x);
  x.head(nf_) = -x.head(nf_);
}

// ---------------------------------------------------------------------------------------------
// the solve

StructuredPath::Outcome StructuredPath::solve(const QpProblem& p, const QpSettings& settings,
                                              std::int8_t* row_side, std::int8_t* bound_side,
                                              Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<Eigen::VectorXd> y,
                                              Eigen::Ref<Eigen::VectorXd> lambda,
                                              Eigen::Ref<Eigen::VectorXd> mu, QpInfo& info) noexcept {
  refinements_ = 0;
  changes_ = 0;
  const int n = p.n();
  if (n == 0 || n > max_n_ || p.me() > max_me_ || p.mi() > max_mi_) return Outcome::NotStructured;
  const auto H = p.H();

  // 1. structure and convexity of H
  if (part_n_ != n || !blocksHold(H)) detectBlocks(H);
  if (!structured_) return Outcome::NotStructured;
  const double scale = H.diagonal().maxCoeff();
  if (!(scale > 0.0)) return Outcome::NotDefinite;
  const double threshold = settings.definiteness_tolerance * scale;
  if (!factorFullBlocks(H, threshold)) return Outcome::NotDefinite;

  // 2.–7. the guessed active set, changed while the answer says how (a primal–dual active-set step:
  // wrong-sign multipliers released, violated constraints made active)
  for (int guess = 0;; ++guess) {
    int changes = 0;
    const Outcome o =
        solveGuess(p, settings, threshold, row_side, bound_side, x, y, lambda, mu, info, changes);
    changes_ += changes;
    if (o != Outcome::WrongActiveSet || changes == 0 || changes > kMaxChangesPerGuess ||
        guess == kMaxGuessChanges) {
      info.iterations = changes_;
      return o;
    }
  }
}

StructuredPath::Outcome StructuredPath::solveGuess(
    const QpProblem& p, const QpSettings& settings, double threshold, std::int8_t* row_side,
    std::int8_t* bound_side, Eigen::Ref<Eigen::VectorXd> x, Eigen::Ref<Eigen::VectorXd> y,
    Eigen::Ref<Eigen::VectorXd> lambda, Eigen::Ref<Eigen::VectorXd> mu, QpInfo& info, int& changes) noexcept {
  const int n = p.n(), me = p.me(), mi = p.mi();
  const auto H = p.H();
  const auto A = p.A();
  const auto C = p.C();
  const auto g = p.g();
  const auto b = p.b();
  const auto l = p.l();
  const auto u = p.u();
  const auto xl = p.xl();
  const auto xu = p.xu();

  // 2. the active set: bound-fixed variables B (fixed or at an active bound), free variables F,
  // equality rows E (rows of A, rows of C with l = u, active rows of C)
  nf_ = 0;
  int nbl = 0, fixed = 0;
  for (int j = 0; j < n; ++j) {
    const double lo = xl(j), up = xu(j);
    const auto uj = static_cast<std::size_t>(j);
    double v = 0.0;
    bool at_bound = true;
    if (lo == up) {
      v = lo;
      ++fixed;
    } else if (bound_side[uj] > 0 && lo > -kInf) {
      v = lo;
    } else if (bound_side[uj] < 0 && up < kInf) {
      v = up;
    } else {
      at_bound = false;
    }
    xb_(j) = v;
    if (at_bound) {
      pos_[uj] = -1;
      bound_list_[static_cast<std::size_t>(nbl++)] = j;
    } else {
      pos_[uj] = nf_;
      free_[static_cast<std::size_t>(nf_++)] = j;
    }
  }
  ne_ = 0;
  for (int i = 0; i < me; ++i) {
    esrc_[static_cast<std::size_t>(ne_)] = i;
    e_(ne_++) = b(i);
  }
  int ceq = 0;
  for (int i = 0; i < mi; ++i) {
    const double lo = l(i), up = u(i);
    const std::int8_t side = row_side[static_cast<std::size_t>(i)];
    double v;
    if (lo == up) {
      v = lo;
      ++ceq;
    } else if (side > 0 && lo > -kInf) {
      v = lo;
    } else if (side < 0 && up < kInf) {
      v = up;
    } else {
      continue;
    }
    esrc_[static_cast<std::size_t>(ne_)] = i;
    e_(ne_++) = v;
  }
  if (ne_ > nf_) return Outcome::Dependent;
  if (!factorFreeBlocks(H, threshold)) return Outcome::NotDefinite;

  // 3. W = L⁻¹E_Fᵀ with its column ranges, e − E_B x_B, S = WᵀW = L_S L_Sᵀ
  for (int r = 0; r < ne_; ++r) {
    const int i = esrc_[static_cast<std::size_t>(r)];
    // row i of A or C: entry j at row[j · stride]
    const double* row = r < me ? A.data() + i : C.data() + i;
    const Eigen::Index stride = r < me ? A.outerStride() : C.outerStride();
    double* w = W_.col(r).data();
    for (int f = 0; f < nf_; ++f) w[f] = row[free_[static_cast<std::size_t>(f)] * stride];
    double fixed_part = 0.0;
    for (int k = 0; k < nbl; ++k) {
      const int j = bound_list_[static_cast<std::size_t>(k)];
      fixed_part += row[j * stride] * xb_(j);
    }
    e_(r) -= fixed_part;
    int first = 0, last = nf_ - 1;
    while (first < nf_ && w[first] == 0.0) ++first;
    if (first == nf_) return Outcome::Dependent;  // no free variable in the row
    while (w[last] == 0.0) --last;
    solveL(W_.col(r), first, last);
    first_[static_cast<std::size_t>(r)] = first;
    last_[static_cast<std::size_t>(r)] = last;
  }
  // S = WᵀW (upper triangle, column by column) and S = UᵀU up-looking: every product is a dot of
  // contiguous column segments
  for (int k = 0; k < ne_; ++k) {
    const int fk = first_[static_cast<std::size_t>(k)], lk = last_[static_cast<std::size_t>(k)];
    for (int r = 0; r <= k; ++r) {
      const int lo = std::max(fk, first_[static_cast<std::size_t>(r)]);
      const int hi = std::min(lk, last_[static_cast<std::size_t>(r)]);
      S_(r, k) = lo <= hi ? W_.col(k).segment(lo, hi - lo + 1).dot(W_.col(r).segment(lo, hi - lo + 1)) : 0.0;
    }
  }
  for (int k = 0; k < ne_; ++k) {
    auto col = S_.col(k);
    for (int i = 0; i < k; ++i) col(i) = (col(i) - S_.col(i).head(i).dot(col.head(i))) / S_(i, i);
    const double d = col(k) - col.head(k).squaredNorm();
    if (!(d > kDependentPivot * col(k))) return Outcome::Dependent;
    col(k) = std::sqrt(d);
  }

  // 4. the KKT point of the free variables: gradient g_F + H_FB x_B
  hessianTimes(H, xb_, hx_);
  for (int f = 0; f < nf_; ++f) {
    const int j = free_[static_cast<std::size_t>(f)];
    rf_(f) = g(j) + hx_(j);
  }
  solveKkt(rf_, e_, xf_, nu_);

  // 5. multipliers and residuals, refined while the linear solve is not accurate to the
  // tolerances the dense path works with
  const double ptol = settings.primal_tolerance, dtol = settings.dual_tolerance;
  auto xv = x.head(n);
  double dual_scale = 1.0, stat = 0.0, eq_err = 0.0;
  int refined = 0;
  for (;;) {
    for (int j = 0; j < n; ++j) {
      const int f = pos_[static_cast<std::size_t>(j)];
      xv(j) = f >= 0 ? xf_(f) : xb_(j);
    }
    y.head(me) = nu_.head(me);
    lambda.head(mi).setZero();
    ctl_.head(n).setZero();
    for (int r = me; r < ne_; ++r) {
      const int i = esrc_[static_cast<std::size_t>(r)];
      lambda(i) = nu_(r);
      ctl_.head(n) += nu_(r) * C.row(i).transpose();
    }
    hessianTimes(H, xv, hx_);
    if (me > 0)
      aty_.head(n).noalias() = A.transpose() * y.head(me);
    else
      aty_.head(n).setZero();
    res_.head(n) = hx_.head(n) + g + aty_.head(n) + ctl_.head(n);
    mu.head(n).setZero();
    for (int k = 0; k < nbl; ++k) {
      const int j = bound_list_[static_cast<std::size_t>(k)];
      mu(j) = -res_(j);
    }
    if (me > 0) ax_.head(me).noalias() = A * xv;
    if (mi > 0) cx_.head(mi).noalias() = C * xv;
    // the residual of the linear system: stationarity on F, the equality and active rows
    dual_scale = std::max({1.0, hx_.head(n).lpNorm<Eigen::Infinity>(), g.lpNorm<Eigen::Infinity>(),
                           mu.head(n).lpNorm<Eigen::Infinity>(), aty_.head(n).lpNorm<Eigen::Infinity>(),
                           ctl_.head(n).lpNorm<Eigen::Infinity>()});
    stat = 0.0;
    for (int f = 0; f < nf_; ++f) {
      const double rj = res_(free_[static_cast<std::size_t>(f)]);
      rf_(f) = rj;
      stat = std::max(stat, std::abs(rj));
    }
    eq_err = 0.0;
    for (int r = 0; r < ne_; ++r) {
      const int i = esrc_[static_cast<std::size_t>(r)];
      double target, value;
      if (r < me) {
        target = b(i);
        value = ax_(i);
      } else {
        target = l(i) == u(i) || row_side[static_cast<std::size_t>(i)] > 0 ? l(i) : u(i);
        value = cx_(i);
      }
      re_(r) = target - value;
      eq_err = std::max(eq_err, std::abs(value - target) / std::max(1.0, std::abs(target)));
    }
    if ((stat <= kRefineTarget * dual_scale && eq_err <= kRefineTarget) || refined >= kMaxRefinements) break;
    // one step of iterative refinement: the correction solves the same KKT system with the
    // residuals as right-hand side
    ++refined;
    ++refinements_;
    solveKkt(rf_, re_, dxf_, dnu_);
    xf_.head(nf_) += dxf_.head(nf_);
    nu_.head(ne_) += dnu_.head(ne_);
  }

  // 6. is the guess the optimum? no inactive constraint violated (beyond the dense path's test for
  // adding one) and every active multiplier of the right sign (u = −side·multiplier ≥ 0 up to
  // rounding). If not, the next guess makes the violated ones active and releases the wrong-sign
  // ones.
  const double xnorm = xv.lpNorm<Eigen::Infinity>();
  auto violation = [&](double value, double lo, double up, int row) -> std::int8_t {
    const double vlo = lo - value, vup = value - up;
    const double viol = std::max(vlo, vup);
    const double bound = vlo > vup ? lo : up;
    if (!(viol > ptol * std::max(1.0, std::abs(bound)))) return 0;
    const double rn = row >= 0 ? C.row(row).norm() : 1.0;  // only when it matters
    if (!(viol > ptol * std::max({1.0, std::abs(bound), rn * xnorm}))) return 0;
    return vlo > vup ? 1 : -1;
  };
  for (int i = 0; i < mi; ++i) {
    auto& side = row_side[static_cast<std::size_t>(i)];
    if (side != 0 || l(i) == u(i)) continue;
    side = violation(cx_(i), l(i), u(i), i);
    changes += side != 0;
  }
  for (int j = 0; j < n; ++j) {
    if (pos_[static_cast<std::size_t>(j)] < 0) continue;
    auto& side = bound_side[static_cast<std::size_t>(j)];
    side = violation(xv(j), xl(j), xu(j), -1);
    changes += side != 0;
  }
  double umax = 1.0, umin = 0.0;
  for (int k = 0; k < nbl; ++k) {
    const int j = bound_list_[static_cast<std::size_t>(k)];
    if (xl(j) == xu(j)) continue;
    const double uk = bound_side[static_cast<std::size_t>(j)] > 0 ? -mu(j) : mu(j);
    umax = std::max(umax, std::abs(uk));
    umin = std::min(umin, uk);
  }
  for (int r = me; r < ne_; ++r) {
    const int i = esrc_[static_cast<std::size_t>(r)];
    if (l(i) == u(i)) continue;
    const double uk = row_side[static_cast<std::size_t>(i)] > 0 ? -lambda(i) : lambda(i);
    umax = std::max(umax, std::abs(uk));
    umin = std::min(umin, uk);
  }
  // released below −kAccurate·umax, stricter than the dense path's −dual_tolerance·umax: a
  // multiplier between the two would be reported as 0 with its size left in the stationarity,
  // a solution of the tolerance's accuracy only; releasing it gives the exact optimum
  const double drop = -std::min(dtol, kAccurate) * umax;
  if (umin < drop) {
    for (int k = 0; k < nbl; ++k) {
      const int j = bound_list_[static_cast<std::size_t>(k)];
      auto& side = bound_side[static_cast<std::size_t>(j)];
      if (xl(j) != xu(j) && (side > 0 ? -mu(j) : mu(j)) < drop) {
        side = 0;
        ++changes;
      }
    }
    for (int r = me; r < ne_; ++r) {
      const int i = esrc_[static_cast<std::size_t>(r)];
      auto& side = row_side[static_cast<std::size_t>(i)];
      if (l(i) != u(i) && (side > 0 ? -lambda(i) : lambda(i)) < drop) {
        side = 0;
        ++changes;
      }
    }
  }
  if (changes > 0) return Outcome::WrongActiveSet;
  if (!(stat <= kAccurate * dual_scale) || !(eq_err <= kAccurate)) return Outcome::Inaccurate;
  const double sign_error = -umin;
  // a wrong sign within the tolerance is rounding: reported as 0, its size stays in the residual
  double dual_res = stat;  // ‖Hx + g + Aᵀy + Cᵀλ + μ‖∞: zero on B by the choice of μ_B
  if (umin < 0.0) {
    for (int k = 0; k < nbl; ++k) {
      const int j = bound_list_[static_cast<std::size_t>(k)];
      if (xl(j) != xu(j) && (bound_side[static_cast<std::size_t>(j)] > 0 ? mu(j) > 0.0 : mu(j) < 0.0))
        mu(j) = 0.0;
    }
    for (int r = me; r < ne_; ++r) {
      const int i = esrc_[static_cast<std::size_t>(r)];
      if (l(i) != u(i) && (row_side[static_cast<std::size_t>(i)] > 0 ? lambda(i) > 0.0 : lambda(i) < 0.0)) {
        res_.head(n) -= lambda(i) * C.row(i).transpose();
        lambda(i) = 0.0;
      }
    }
    dual_res = (res_.head(n) + mu.head(n)).lpNorm<Eigen::Infinity>();
  }
  // primal violation and complementarity of one side lo ≤ value ≤ up with multiplier m, as
  // QpSolver's KKT check
  double pabs = 0.0, prel = 0.0, comp = 0.0, crel = 0.0;
  auto account = [&](double value, double lo, double up, double m) {
    const double vlo = lo - value, vup = value - up;
    if (vlo > 0.0) {
      pabs = std::max(pabs, vlo);
      prel = std::max(prel, vlo / std::max(1.0, std::abs(lo)));
    }
    if (vup > 0.0) {
      pabs = std::max(pabs, vup);
      prel = std::max(prel, vup / std::max(1.0, std::abs(up)));
    }
    if (m != 0.0) {
      const double side_bound = m < 0.0 ? lo : up;
      const double am = std::abs(m), dist = std::abs(value - side_bound);
      comp = std::max(comp, am * dist);
      crel = std::max(crel, am * dist / (std::max(1.0, am) * std::max(1.0, std::abs(side_bound))));
    }
  };
  for (int i = 0; i < me; ++i) account(ax_(i), b(i), b(i), 0.0);
  for (int i = 0; i < mi; ++i) account(cx_(i), l(i), u(i), lambda(i));
  for (int j = 0; j < n; ++j) account(xv(j), xl(j), xu(j), mu(j));

  // 7. the solver's KKT check on the original data
  const double tol = settings.kkt_tolerance;
  const double dual_scaled = dual_res / dual_scale;
  if (!(prel <= tol) || !(dual_scaled <= tol) || !(crel <= tol) || !(sign_error <= tol * umax))
    return Outcome::Inaccurate;
  info.proximal_iterations = 0;
  info.regularized = false;
  info.rho = 0.0;
  info.equality_rank = me + ceq + fixed;
  info.dependent_equalities = 0;
  info.objective = xv.dot(0.5 * hx_.head(n) + g);
  info.primal_residual = pabs;
  info.dual_residual = dual_res;
  info.complementarity = comp;
  return Outcome::Solved;
}

}  // namespace mrqp::qp
